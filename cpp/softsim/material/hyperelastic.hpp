#pragma once
// The plug-in point for constitutive laws: the finite-strain element formulations (TLED, ANP;
// fem/element_kind.hpp) ask a law for its stress and tangent through the functions below and
// know nothing else of it. The small-strain formulations (linear, corotational) use the
// (E, ν) the law linearises to.
//
// A law is a plain struct of parameters (neo_hookean.hpp, mooney_rivlin.hpp) with these free
// functions in namespace softsim::material, F the deformation gradient, C = FᵀF:
//
//   std::string     law_name(const Law&);                                   its material.model name
//   double          strain_energy_density(const Law&, const Matrix3d& F);   W per reference volume
//   Matrix3d        second_piola(const Law&, const Matrix3d& C);            S = 2 ∂W/∂C
//   Matrix3d        first_piola(const Law&, const Matrix3d& F);             P = F S = ∂W/∂F
//   LawLinearisation linearise(const Law&, const Matrix3d& F);              set-up at F, then
//   Matrix3d        first_piola_increment(const Law&, const LawLinearisation&, const Matrix3d& dF);
//                                                                           dP(F)[dF], the static tangent
//   double          volumetric_modulus(const Law&);                         κ of U(J) = κ/2 (J − 1)²
//   Law             isochoric_part(const Law&);                             the law without U(J)
//
// The last two are the split W = W_iso(F) + U(J) the average-nodal-pressure element (ANP) needs:
// it evaluates W_iso per element and U at the nodes (fem/nodal_pressure.hpp).
//
// Adding a law X:
//   1. material/x.hpp, .cpp: struct X and the functions above; first_piola inline in the header,
//      since the explicit TLED and ANP kernels evaluate it per element with X as a template
//      parameter (fem/law_kernels.hpp) — no virtual call, no switch inside the element loop;
//   2. X and XLinearisation into the two variants below;
//   3. a branch of hybrid/dhd_config.cpp's read_material reading its parameters (and its
//      config keys in cpp/apps/dhd_sim.md), giving the small-strain (E, ν) it linearises to;
//   4. tests: a homogeneous deformation against the analytic stress, P and dP against finite
//      differences of W and P, and rigid-rotation invariance (tests/cpp/test_material.cpp).
//   5. only for a law defined, smooth and restoring at J ≤ 0: kInversionRobust<X> = true
//      (inversion_robust.hpp), so its inverted elements get forces and are not failures.
// Nothing else changes: the element set, the static solver, the stress and energy outputs all
// dispatch on HyperelasticLaw.
//
// Laws with more than F: a direction (transversely_isotropic.hpp: a fibre direction, one per
// element through fem::Material::fibres, stored per element slot by the element set) or
// internal variables (viscoelastic.hpp: a Prony series whose tensors per element and term the
// element set stores per slot, double-buffered by step parity, and advances once per explicit
// step). Both run their own kernel (fem/law_kernels.cpp); without internal variables (static
// solver, outputs) the viscoelastic law is its relaxed response. Ogden-type laws written in
// principal stretches fit the interface as it is (P and dP from the eigen-decomposition of C:
// ogden.hpp). The explicit kernels of the laws here are vectorised and tested against their
// first_piola (fem/law_kernels.hpp says which runs which); a new law runs the generic kernel,
// which calls its first_piola per element, until it gets one of its own.
#include <string>
#include <variant>

#include <Eigen/Core>

#include "softsim/material/mooney_rivlin.hpp"
#include "softsim/material/neo_hookean.hpp"
#include "softsim/material/ogden.hpp"
#include "softsim/material/stable_neo_hookean.hpp"
#include "softsim/material/transversely_isotropic.hpp"
#include "softsim/material/viscoelastic.hpp"

namespace softsim::material {

using HyperelasticLaw =
    std::variant<NeoHookean, MooneyRivlin, Ogden, StableNeoHookean, TransverselyIsotropic, Viscoelastic>;
using HyperelasticLinearisation =
    std::variant<NeoHookeanLinearisation, MooneyRivlinLinearisation, OgdenLinearisation, StableNeoHookeanLinearisation,
                 TransverselyIsotropicLinearisation, ViscoelasticLinearisation>;

// "neo_hookean_paper", "neo_hookean_decoupled", "mooney_rivlin", "ogden", "stable_neo_hookean",
// "transversely_isotropic" (the config's material.model), or a base's name with "+prony".
std::string law_name(const HyperelasticLaw& law);

// The interface above on the variant: one dispatch per call, for the paths that take one
// element at a time (static solver, stress and energy outputs). The explicit kernels dispatch
// once per range of elements instead (fem/law_kernels.hpp).
double strain_energy_density(const HyperelasticLaw& law, const Eigen::Matrix3d& F);
Eigen::Matrix3d second_piola(const HyperelasticLaw& law, const Eigen::Matrix3d& C);
Eigen::Matrix3d first_piola(const HyperelasticLaw& law, const Eigen::Matrix3d& F);
HyperelasticLinearisation linearise(const HyperelasticLaw& law, const Eigen::Matrix3d& F);
Eigen::Matrix3d first_piola_increment(const HyperelasticLaw& law, const HyperelasticLinearisation& at,
                                      const Eigen::Matrix3d& dF);
double volumetric_modulus(const HyperelasticLaw& law);
HyperelasticLaw isochoric_part(const HyperelasticLaw& law);
// kInversionRobust (inversion_robust.hpp) of the law the variant holds.
bool inversion_robust(const HyperelasticLaw& law);

// The law's fibre direction (nullptr: isotropic) and its replacement (viscoelastic.hpp).
const Eigen::Vector3d* fibre_of(const HyperelasticLaw& law);
void set_fibre(HyperelasticLaw& law, const Eigen::Vector3d& a);
// Doubles of internal state per element (0: none).
int state_size(const HyperelasticLaw& law);

}  // namespace softsim::material
