#pragma once
// Visco-hyperelasticity with Prony-series relaxation of the isochoric stress, in the form
// Taylor et al. made real-time for TLED (Taylor, Crozier, Ourselin, MICCAI 2008; Taylor et
// al., Med. Image Anal. 2009, "On modelling of anisotropic viscoelasticity for soft tissue
// simulation"): a base hyperelastic law W = W_iso + U(J) whose isochoric second Piola stress
// is convolved with the normalised relaxation function
//
//   g(t) = g∞ + Σᵢ gᵢ exp(−t/τᵢ),  g∞ = 1 − Σᵢ gᵢ  (gᵢ ≥ 0, Σ gᵢ < 1, τᵢ > 0),
//   S(t) = S_vol(t) + ∫₀ᵗ g(t − s) dS_iso/ds ds = S_base(t) − Σᵢ Aᵢ(t),
//   Aᵢ(t) = ∫₀ᵗ (gᵢ/τᵢ) exp(−(t − s)/τᵢ) S_iso(s) ds      (dAᵢ/dt = (gᵢ S_iso − Aᵢ)/τᵢ),
//
// one symmetric tensor Aᵢ per term and element: the law's internal variables. The explicit
// engine advances them once per step by the exponential recursion
//
//   Aᵢⁿ = eᵢ Aᵢⁿ⁻¹ + gᵢ (1 − eᵢ) S_iso(Fⁿ),  eᵢ = exp(−Δt/τᵢ),
//
// the exact solution of the ODE above with S_iso held at its value of step n over the step
// that ends there (Taylor et al. integrate the same ODE by backward Euler, eᵢ → τᵢ/(Δt + τᵢ),
// its first-order expansion). A step strain held from step 0 on therefore gives exactly the
// Prony series S_vol + S_iso g(tₙ + Δt). Limits: gᵢ = 0 leaves Aᵢ = 0 and the base law bit for
// bit; τᵢ → 0 (eᵢ = 0) gives the relaxed law at once, τᵢ → ∞ (eᵢ = 1) the instantaneous one.
//
// Without internal variables (the static solver, stress and energy outputs) the law is its
// relaxed (long-term) response, the limit t → ∞ of a held deformation:
//   W∞ = U(J) + g∞ W_iso,  P∞ = P_base − (1 − g∞) P_iso.
// Its small-strain constants are the base law's instantaneous ones (the stiffest response,
// which sets the critical step).
#include <array>
#include <string>
#include <variant>

#include <Eigen/Core>

#include "softsim/material/mooney_rivlin.hpp"
#include "softsim/material/neo_hookean.hpp"
#include "softsim/material/ogden.hpp"
#include "softsim/material/transversely_isotropic.hpp"

namespace softsim::material {

// The laws a Prony series can relax: those with an isochoric/volumetric split (the paper's
// neo-Hookean form has none: its "isochoric" part −μ ln J changes volume).
using ElasticLaw = std::variant<NeoHookean, MooneyRivlin, Ogden, TransverselyIsotropic>;
using ElasticLinearisation = std::variant<NeoHookeanLinearisation, MooneyRivlinLinearisation, OgdenLinearisation,
                                          TransverselyIsotropicLinearisation>;

struct Viscoelastic {
  static constexpr int kMaxTerms = 4;
  ElasticLaw base;
  int terms = 0;
  std::array<double, kMaxTerms> g{};    // gᵢ, dimensionless
  std::array<double, kMaxTerms> tau{};  // τᵢ (s)

  double long_term() const {  // g∞ = 1 − Σ gᵢ
    double s = 0;
    for (int i = 0; i < terms; ++i) s += g[i];
    return 1.0 - s;
  }
  // Doubles of internal state per element: the six components of each Aᵢ.
  int state_size() const { return 6 * terms; }
};

// The base law's name with "+prony" ("neo_hookean_decoupled+prony", ...).
std::string law_name(const Viscoelastic& law);
// Throws InputError unless 1 ≤ terms ≤ 4, every gᵢ ≥ 0 and τᵢ > 0 (finite) and Σ gᵢ < 1, and
// the base is not the paper's neo-Hookean form.
void validate_moduli(const Viscoelastic& law);

// The relaxed (long-term) law, see above.
double strain_energy_density(const Viscoelastic& law, const Eigen::Matrix3d& F);
Eigen::Matrix3d second_piola(const Viscoelastic& law, const Eigen::Matrix3d& C);
Eigen::Matrix3d first_piola(const Viscoelastic& law, const Eigen::Matrix3d& F);
struct ViscoelasticLinearisation {
  ElasticLinearisation base;
  ElasticLinearisation iso;
};
ViscoelasticLinearisation linearise(const Viscoelastic& law, const Eigen::Matrix3d& F);
Eigen::Matrix3d first_piola_increment(const Viscoelastic& law, const ViscoelasticLinearisation& at,
                                      const Eigen::Matrix3d& dF);
double volumetric_modulus(const Viscoelastic& law);
// The same relaxation on the base's isochoric part (for the ANP element).
Viscoelastic isochoric_part(const Viscoelastic& law);

// The base law's isochoric second Piola stress S_iso(C), the quantity the series relaxes.
Eigen::Matrix3d isochoric_second_piola(const Viscoelastic& law, const Eigen::Matrix3d& C);

// The step of the recursion above for one element: Aᵢ (6 components each, xx yy zz xy yz xz,
// term-major) from `state_in` to `state_out` with `decay[i]` = eᵢ for the step, then
// P = F (S_iso + K J (J − 1) C⁻¹ − Σᵢ Aᵢ) (every base a series takes has that U(J)): the base's
// P to round-off where the Aᵢ are zero. `state_in` and `state_out` may be the same.
struct PronyStep {
  std::array<double, Viscoelastic::kMaxTerms> decay{};   // eᵢ
  std::array<double, Viscoelastic::kMaxTerms> weight{};  // gᵢ (1 − eᵢ)
  ElasticLaw isochoric;  // the base's isochoric part, made once per step (and given the
                         // element's fibre with set_fibre where fibres differ per element)
  double bulk = 0;       // K of the base's U(J) = K/2 (J − 1)²
};
PronyStep prony_step(const Viscoelastic& law, double dt);
Eigen::Matrix3d relaxed_first_piola(const Viscoelastic& law, const PronyStep& step, const Eigen::Matrix3d& F,
                                    const double* state_in, double* state_out);
// The law and its step with element fibre `a` (no effect without a fibre).
void set_fibre(Viscoelastic& law, PronyStep& step, const Eigen::Vector3d& a);

// The fibre direction of a law that has one (transversely isotropic, or a series on one),
// else nullptr; `set_fibre` replaces it (no effect on a law without one).
const Eigen::Vector3d* fibre_of(const ElasticLaw& law);
const Eigen::Vector3d* fibre_of(const Viscoelastic& law);
void set_fibre(ElasticLaw& law, const Eigen::Vector3d& a);
void set_fibre(Viscoelastic& law, const Eigen::Vector3d& a);

}  // namespace softsim::material
