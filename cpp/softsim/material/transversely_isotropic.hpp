#pragma once
// A transversely isotropic hyperelastic law: the decoupled neo-Hookean matrix plus a fibre
// term in the isochoric fourth invariant (Taylor, Comas, Cheng, Passenger, Hawkes, Atkinson,
// Ourselin, "On modelling of anisotropic viscoelasticity for soft tissue simulation", Med.
// Image Anal. 2009, and MICCAI 2008; the TI form NiftySim runs), a law of the interface in
// hyperelastic.hpp:
//
//   W = μ/2 (Ī₁ − 3) + η/2 (Ī₄ − 1)² + K/2 (J − 1)²,
//   Ī₁ = J^(−2/3) I₁,  Ī₄ = J^(−2/3) I₄,  I₄ = a·C a,  C = FᵀF,  |a| = 1 (reference fibre),
//   S = μ J^(−2/3) (I − I₁/3 C⁻¹) + 2η (Ī₄ − 1) J^(−2/3) (a⊗a − I₄/3 C⁻¹) + K J (J − 1) C⁻¹,
//   P = F S = μ b (F − I₁/3 F⁻ᵀ) + 2η (Ī₄ − 1) b ((F a)⊗a − I₄/3 F⁻ᵀ) + K J (J − 1) F⁻ᵀ,  b = J^(−2/3).
//
// With η = 0 it is the decoupled neo-Hookean law (neo_hookean.hpp). The fibre direction is the
// law's `fibre`; a direction per element (fem::Material::fibres) replaces it element by element.
// At small strain the fibre adds 16η/9 to the P-wave modulus along a (Ī₄ − 1 ≈ 2 dev ε : a⊗a);
// the isotropic constants it linearises to take μ + 4η/3, the shear modulus whose P-wave
// modulus K + 4μ/3 bounds that, so the critical step stays safe in every direction.
#include <cmath>
#include <string>

#include <Eigen/Core>
#include <Eigen/LU>

#include "softsim/material/elastic.hpp"

namespace softsim::material {

struct TransverselyIsotropic {
  double mu = 0;    // matrix shear modulus (Pa)
  double eta = 0;   // fibre stiffness η (Pa)
  double bulk = 0;  // K (Pa)
  Eigen::Vector3d fibre = Eigen::Vector3d::UnitX();  // unit reference direction a
};

inline void set_fibre(TransverselyIsotropic& law, const Eigen::Vector3d& a) { law.fibre = a; }

// "transversely_isotropic".
std::string law_name(const TransverselyIsotropic& law);
// Throws InputError unless μ > 0, η ≥ 0, K > 0 (finite) and |a| = 1 (to 1e-12).
void validate_moduli(const TransverselyIsotropic& law);
// The isotropic small-strain constants (μ + 4η/3, K) as (E, ν) with `density` (see above).
ElasticParameters small_strain_parameters(const TransverselyIsotropic& law, double density);

double strain_energy_density(const TransverselyIsotropic& law, const Eigen::Matrix3d& F);
Eigen::Matrix3d second_piola(const TransverselyIsotropic& law, const Eigen::Matrix3d& C);

// P = ∂W/∂F, inline for the generic TLED and ANP kernels (fem/law_kernels.hpp).
inline Eigen::Matrix3d first_piola(const TransverselyIsotropic& law, const Eigen::Matrix3d& F) {
  const double J = F.determinant();
  const Eigen::Matrix3d FinvT = F.inverse().transpose();
  const double I1 = F.squaredNorm();  // tr C
  const Eigen::Vector3d Fa = F * law.fibre;
  const double I4 = Fa.squaredNorm();  // a·C a
  const double x = 1.0 / std::cbrt(J);
  const double b = x * x;  // J^(−2/3)
  const double fibre = 2.0 * law.eta * (b * I4 - 1.0) * b;
  return law.mu * b * (F - (I1 / 3.0) * FinvT) + fibre * (Fa * law.fibre.transpose() - (I4 / 3.0) * FinvT) +
         law.bulk * J * (J - 1.0) * FinvT;
}

struct TransverselyIsotropicLinearisation {
  Eigen::Matrix3d F;
};
TransverselyIsotropicLinearisation linearise(const TransverselyIsotropic& law, const Eigen::Matrix3d& F);
Eigen::Matrix3d first_piola_increment(const TransverselyIsotropic& law, const TransverselyIsotropicLinearisation& at,
                                      const Eigen::Matrix3d& dF);

// U(J) = K/2 (J − 1)²; the isochoric part is the law with K = 0.
double volumetric_modulus(const TransverselyIsotropic& law);
TransverselyIsotropic isochoric_part(const TransverselyIsotropic& law);

}  // namespace softsim::material
