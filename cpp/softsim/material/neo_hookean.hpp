#pragma once
// The two compressible neo-Hookean forms the project compares, written as functions of the
// deformation gradient F (first Piola–Kirchhoff stress P = ∂W/∂F = F S):
//
//   paper     (000 eq. 14)   W = μ/2 (I₁ − 3) − μ ln J + λ/2 (J − 1)²
//                            S = μ (I − C⁻¹) + λ J (J − 1) C⁻¹
//   decoupled (Miller et al. 2007 TLED; CalculiX *HYPERELASTIC, NEO HOOKE)
//                            W = C10 (Ī₁ − 3) + (J − 1)² / D1,  Ī₁ = J^(−2/3) I₁,
//                            C10 = μ/2, D1 = 2/K
//                            S = μ J^(−2/3) (I − I₁/3 C⁻¹) + K J (J − 1) C⁻¹
//
// Both linearise to small-strain elasticity with the same μ and λ = K − 2μ/3, so an (E, ν)
// pair means the same material at small strain in every form.
#include <string>

#include <Eigen/Core>

#include "softsim/material/elastic.hpp"

namespace softsim::material {

enum class NeoHookeanForm { paper, decoupled };

// "neo_hookean_paper" / "neo_hookean_decoupled".
std::string form_name(NeoHookeanForm form);

struct NeoHookean {
  NeoHookeanForm form = NeoHookeanForm::paper;
  double mu = 0;      // shear modulus
  double lambda = 0;  // Lamé's first parameter (paper form)
  double bulk = 0;    // K = λ + 2μ/3 (decoupled form)

  static NeoHookean from(NeoHookeanForm form, const ElasticParameters& p);
  double c10() const { return 0.5 * mu; }
  double d1() const { return 2.0 / bulk; }
};

// The law's material.model name: form_name(law.form) (material/hyperelastic.hpp).
std::string law_name(const NeoHookean& law);

// Strain energy per unit reference volume. Requires det F > 0.
double strain_energy_density(const NeoHookean& law, const Eigen::Matrix3d& F);
// P = ∂W/∂F.
Eigen::Matrix3d first_piola(const NeoHookean& law, const Eigen::Matrix3d& F);
// S from the right Cauchy–Green tensor C (000 eq. 14 for the paper form).
Eigen::Matrix3d second_piola(const NeoHookean& law, const Eigen::Matrix3d& C);
// Directional derivative dP = ∂P/∂F : dF (the consistent tangent for Newton).
Eigen::Matrix3d first_piola_increment(const NeoHookean& law, const Eigen::Matrix3d& F,
                                      const Eigen::Matrix3d& dF);

// What dP(F)[·] computes of F alone once for many increments at one F (the 12 columns of an
// element tangent): the decoupled form's J^(−2/3). J and F⁻¹ stay in each increment: taken from
// outside, they change how the compiler fuses the increment's multiply-adds, and with it the
// last bits of dP.
struct NeoHookeanLinearisation {
  Eigen::Matrix3d F;
  double a = 0;  // decoupled: J^(−2/3)
};
NeoHookeanLinearisation linearise(const NeoHookean& law, const Eigen::Matrix3d& F);
// The same dP as first_piola_increment(law, F, dF), from the set-up at F.
Eigen::Matrix3d first_piola_increment(const NeoHookean& law, const NeoHookeanLinearisation& at,
                                      const Eigen::Matrix3d& dF);

// The split W = W_iso(F) + U(J) with U = κ/2 (J − 1)², used by the average-nodal-pressure
// element (fem/nodal_pressure.hpp), which evaluates U at the nodes instead of the element:
//   paper      W_iso = μ/2 (I₁ − 3) − μ ln J,  κ = λ
//   decoupled  W_iso = C10 (Ī₁ − 3),           κ = K
// `isochoric_part` is the same law with κ = 0, so P, W and dP above give W_iso's.
double volumetric_modulus(const NeoHookean& law);
NeoHookean isochoric_part(const NeoHookean& law);

}  // namespace softsim::material
