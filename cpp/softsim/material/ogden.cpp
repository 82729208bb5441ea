#include "softsim/material/ogden.hpp"

#include <algorithm>

#include "softsim/io/errors.hpp"

namespace softsim::material {

std::string law_name(const Ogden&) { return "ogden"; }

void validate_moduli(const Ogden& law) {
  if (law.terms < 1 || law.terms > Ogden::kMaxTerms)
    throw InputError("material: Ogden needs 1 to 3 terms, got " + std::to_string(law.terms));
  for (int p = 0; p < law.terms; ++p)
    if (!std::isfinite(law.mu[p]) || !std::isfinite(law.alpha[p]) || law.alpha[p] == 0.0)
      throw InputError("material: Ogden term " + std::to_string(p + 1) + " needs a finite mu and a finite non-zero alpha");
  const double mu = law.shear_modulus();
  if (!(mu > 0) || !std::isfinite(mu))
    throw InputError("material: Ogden shear modulus sum(mu_p alpha_p) / 2 must be positive, got " + std::to_string(mu));
  if (!(law.bulk > 0) || !std::isfinite(law.bulk))
    throw InputError("material: Ogden bulk modulus K must be positive, got " + std::to_string(law.bulk));
}

ElasticParameters small_strain_parameters(const Ogden& law, double density) {
  const double mu = law.shear_modulus();
  return from_shear_bulk(mu, law.bulk, density);
}

double strain_energy_density(const Ogden& law, const Eigen::Matrix3d& F) {
  const double J = F.determinant();
  const Eigen::Vector3d c = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(F.transpose() * F).eigenvalues();
  const double a = 1.0 / std::cbrt(J * J);
  double w = 0.5 * law.bulk * (J - 1.0) * (J - 1.0);
  for (int p = 0; p < law.terms; ++p) {
    double sum = 0;
    for (int i = 0; i < 3; ++i) sum += std::pow(a * c[i], 0.5 * law.alpha[p]);
    w += law.mu[p] / law.alpha[p] * (sum - 3.0);
  }
  return w;
}

Eigen::Matrix3d second_piola(const Ogden& law, const Eigen::Matrix3d& C) {
  const double J = std::sqrt(C.determinant());
  return ogden_detail::isochoric_second_piola(law, C, J) + law.bulk * J * (J - 1.0) * C.inverse();
}

// The tangent of S_iso = Σ_i s_i(c) N_i ⊗ N_i, an isotropic function of C, in the eigenbasis
// (dC' = Nᵀ dC N; Holzapfel 2000 §6.5, eqs. 6.199–6.200 written for S instead of the spatial tangent):
//   dS'_ii = Σ_j ∂s_i/∂c_j dC'_jj,   dS'_ij = (s_i − s_j)/(c_i − c_j) dC'_ij  (i ≠ j),
// with, from b_i = λ̄_i^α = (J^(−2/3) c_i)^(α/2) and ∂ln b_i/∂c_j = α/(2 c_j) (δ_ij − ⅓),
//   ∂β_i/∂c_j = Σ_p μ_p α_p / (2 c_j) (b_i δ_ij − b_i/3 − b_j/3 + Σ_k b_k / 9).
// For c_i → c_j the quotient loses digits as eps / |c_i − c_j| and tends to
// ∂s_i/∂c_i − ∂s_i/∂c_j; the mean of that limit taken at i and at j equals the quotient to
// O((c_i − c_j)²), so below a relative gap of 1e-5 (eps^(1/3), where both errors meet) it is used.
OgdenLinearisation linearise(const Ogden& law, const Eigen::Matrix3d& F) {
  OgdenLinearisation at;
  at.F = F;
  const double J = F.determinant();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(F.transpose() * F);
  const Eigen::Vector3d c = eig.eigenvalues();
  at.N = eig.eigenvectors();
  const double a = 1.0 / std::cbrt(J * J);
  Eigen::Vector3d beta = Eigen::Vector3d::Zero();
  Eigen::Matrix3d dbeta = Eigen::Matrix3d::Zero();  // ∂β_i/∂c_j
  for (int p = 0; p < law.terms; ++p) {
    Eigen::Vector3d b;
    for (int i = 0; i < 3; ++i) b[i] = std::pow(a * c[i], 0.5 * law.alpha[p]);
    const double B = b.sum();
    beta += law.mu[p] * (b.array() - B / 3.0).matrix();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        dbeta(i, j) += law.mu[p] * law.alpha[p] / (2.0 * c[j]) *
                       ((i == j ? b[i] : 0.0) - b[i] / 3.0 - b[j] / 3.0 + B / 9.0);
  }
  const Eigen::Vector3d s = beta.cwiseQuotient(c);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) at.D(i, j) = dbeta(i, j) / c[i] - (i == j ? s[i] / c[i] : 0.0);
  at.G.setZero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (i == j) continue;
      const double gap = c[i] - c[j];
      at.G(i, j) = std::abs(gap) > 1e-5 * std::max(c[i], c[j])
                       ? (s[i] - s[j]) / gap
                       : 0.5 * ((at.D(i, i) - at.D(i, j)) + (at.D(j, j) - at.D(j, i)));
    }
  at.S_iso = at.N * s.asDiagonal() * at.N.transpose();
  return at;
}

// dP = dF S_iso + F dS_iso[dC] + the volumetric term's increment, as in mooney_rivlin.cpp.
Eigen::Matrix3d first_piola_increment(const Ogden& law, const OgdenLinearisation& at, const Eigen::Matrix3d& dF) {
  const Eigen::Matrix3d& F = at.F;
  const Eigen::Matrix3d dC = dF.transpose() * F + F.transpose() * dF;
  const Eigen::Matrix3d dCp = at.N.transpose() * dC * at.N;
  Eigen::Matrix3d dSp = at.G.cwiseProduct(dCp);
  const Eigen::Vector3d ds = at.D * dCp.diagonal();
  for (int i = 0; i < 3; ++i) dSp(i, i) = ds[i];
  const Eigen::Matrix3d dS = at.N * dSp * at.N.transpose();
  const double J = F.determinant();
  const Eigen::Matrix3d Finv = F.inverse();
  const Eigen::Matrix3d FinvT = Finv.transpose();
  const double dJ = J * (Finv * dF).trace();
  const Eigen::Matrix3d dFinvT = -FinvT * dF.transpose() * FinvT;
  return dF * at.S_iso + F * dS + law.bulk * ((2.0 * J - 1.0) * dJ * FinvT + J * (J - 1.0) * dFinvT);
}

double volumetric_modulus(const Ogden& law) { return law.bulk; }

Ogden isochoric_part(const Ogden& law) {
  Ogden iso = law;
  iso.bulk = 0.0;
  return iso;
}

}  // namespace softsim::material
