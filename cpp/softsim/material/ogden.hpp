#pragma once
// The compressible (decoupled) N-term Ogden law, a hyperelastic law of the interface in
// hyperelastic.hpp (Ogden 1972; Holzapfel 2000 §6.5; CalculiX *HYPERELASTIC, OGDEN):
//
//   W = Σ_p (μ_p/α_p) (λ̄₁^α_p + λ̄₂^α_p + λ̄₃^α_p − 3) + K/2 (J − 1)²,   p = 1..N, N ≤ 3,
//
// λ̄_i = J^(−1/3) λ_i the isochoric principal stretches, λ_i² = c_i the eigenvalues of C = FᵀF
// with eigenvectors N_i. The volumetric term is the one of the decoupled neo-Hookean and
// Mooney–Rivlin laws (neo_hookean.hpp, mooney_rivlin.hpp), so the three differ only in W_iso.
// In principal axes (Holzapfel 2000 eq. 6.194):
//
//   β_i = ∂W_iso/∂ln λ_i = Σ_p μ_p (λ̄_i^α_p − ⅓ Σ_k λ̄_k^α_p),
//   S   = Σ_i (β_i / c_i) N_i ⊗ N_i + K J (J − 1) C⁻¹,   P = F S.
//
// Equal principal stretches: S needs no special case, since equal c_i give equal β_i / c_i and
// any orthonormal basis of the shared eigenspace gives the same S. The tangent does: its
// off-diagonal coefficient (s_i − s_j)/(c_i − c_j) is replaced, for |c_i − c_j| below a relative
// 1e-5, by its closed-form limit ∂s_i/∂c_i − ∂s_i/∂c_j, averaged over i and j, which is exact
// to O((c_i − c_j)²) (ogden.cpp). No perturbation of the stretches.
//
// One term with α = 2 is the decoupled neo-Hookean law with μ = μ₁; two terms with α = (2, −2)
// are Mooney–Rivlin with C10 = μ₁/2, C01 = −μ₂/2. At small strain it is linear elasticity with
// shear modulus μ = ½ Σ_p μ_p α_p and bulk modulus K.
#include <array>
#include <cmath>
#include <string>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "softsim/material/elastic.hpp"

namespace softsim::material {

struct Ogden {
  static constexpr int kMaxTerms = 3;
  int terms = 0;                       // N, 1..3
  std::array<double, kMaxTerms> mu{};  // μ_p (Pa)
  std::array<double, kMaxTerms> alpha{};
  double bulk = 0;  // K (Pa)

  // ½ Σ_p μ_p α_p: the small-strain shear modulus.
  double shear_modulus() const {
    double m = 0;
    for (int p = 0; p < terms; ++p) m += 0.5 * mu[p] * alpha[p];
    return m;
  }
};

// "ogden".
std::string law_name(const Ogden& law);
// Throws InputError unless 1 ≤ N ≤ 3, every α_p is finite and non-zero, every μ_p finite,
// Σ μ_p α_p > 0 and K > 0 (finite): a positive small-strain shear and bulk modulus.
void validate_moduli(const Ogden& law);
// The small-strain constants it linearises to (μ = ½ Σ μ_p α_p, K) as (E, ν) with `density`.
ElasticParameters small_strain_parameters(const Ogden& law, double density);

double strain_energy_density(const Ogden& law, const Eigen::Matrix3d& F);

namespace ogden_detail {
// S_iso = Σ_i s_i N_i ⊗ N_i from the eigen-decomposition of C (β_i / c_i above).
inline Eigen::Matrix3d isochoric_second_piola(const Ogden& law, const Eigen::Matrix3d& C, double J) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C);
  const Eigen::Vector3d c = eig.eigenvalues();
  const double a = 1.0 / std::cbrt(J * J);  // J^(−2/3): c̄_i = a c_i = λ̄_i²
  Eigen::Vector3d beta = Eigen::Vector3d::Zero();
  for (int p = 0; p < law.terms; ++p) {
    Eigen::Vector3d b;
    for (int i = 0; i < 3; ++i) b[i] = std::pow(a * c[i], 0.5 * law.alpha[p]);  // λ̄_i^α_p
    beta += law.mu[p] * (b.array() - b.sum() / 3.0).matrix();
  }
  const Eigen::Matrix3d& N = eig.eigenvectors();
  return N * beta.cwiseQuotient(c).asDiagonal() * N.transpose();
}
}  // namespace ogden_detail

Eigen::Matrix3d second_piola(const Ogden& law, const Eigen::Matrix3d& C);

// P = F S, inline: the TLED and ANP kernels evaluate it per element with the law as a template
// parameter (fem/law_kernels.hpp).
inline Eigen::Matrix3d first_piola(const Ogden& law, const Eigen::Matrix3d& F) {
  const double J = F.determinant();
  const Eigen::Matrix3d FinvT = F.inverse().transpose();
  return F * ogden_detail::isochoric_second_piola(law, F.transpose() * F, J) + law.bulk * J * (J - 1.0) * FinvT;
}

// dP(F)[dF]: the eigen-decomposition of C and the coefficients of dS in its basis, once for
// the 12 columns of an element tangent.
struct OgdenLinearisation {
  Eigen::Matrix3d F;
  Eigen::Matrix3d N;      // eigenvectors of C (columns)
  Eigen::Matrix3d S_iso;  // Σ_i s_i N_i ⊗ N_i
  Eigen::Matrix3d D;      // ∂s_i/∂c_j: the diagonal of dS' from the diagonal of dC'
  Eigen::Matrix3d G;      // (s_i − s_j)/(c_i − c_j), i ≠ j, or its limit
};
OgdenLinearisation linearise(const Ogden& law, const Eigen::Matrix3d& F);
Eigen::Matrix3d first_piola_increment(const Ogden& law, const OgdenLinearisation& at, const Eigen::Matrix3d& dF);

// The split W = W_iso(F) + U(J), U = κ/2 (J − 1)² with κ = K (for the average-nodal-pressure
// element): `isochoric_part` is the law with K = 0.
double volumetric_modulus(const Ogden& law);
Ogden isochoric_part(const Ogden& law);

}  // namespace softsim::material
