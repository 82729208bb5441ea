#include "softsim/material/transversely_isotropic.hpp"

#include "softsim/io/errors.hpp"
#include "softsim/material/isochoric_increment.hpp"

namespace softsim::material {

std::string law_name(const TransverselyIsotropic&) { return "transversely_isotropic"; }

void validate_moduli(const TransverselyIsotropic& law) {
  if (!(law.mu > 0) || !std::isfinite(law.mu))
    throw InputError("material: transversely isotropic mu must be positive, got " + std::to_string(law.mu));
  if (!(law.eta >= 0) || !std::isfinite(law.eta))
    throw InputError("material: transversely isotropic eta must be non-negative, got " + std::to_string(law.eta));
  if (!(law.bulk > 0) || !std::isfinite(law.bulk))
    throw InputError("material: transversely isotropic bulk modulus K must be positive, got " + std::to_string(law.bulk));
  if (!(std::abs(law.fibre.norm() - 1.0) <= 1e-12))
    throw InputError("material: the fibre direction must be a unit vector");
}

ElasticParameters small_strain_parameters(const TransverselyIsotropic& law, double density) {
  const double mu = law.mu + 4.0 * law.eta / 3.0;
  return from_shear_bulk(mu, law.bulk, density);
}

double strain_energy_density(const TransverselyIsotropic& law, const Eigen::Matrix3d& F) {
  const double J = F.determinant();
  const double b = std::pow(J, -2.0 / 3.0);
  const double I1 = F.squaredNorm();
  const double I4 = (F * law.fibre).squaredNorm();
  const double d4 = b * I4 - 1.0;
  return 0.5 * law.mu * (b * I1 - 3.0) + 0.5 * law.eta * d4 * d4 + 0.5 * law.bulk * (J - 1.0) * (J - 1.0);
}

Eigen::Matrix3d second_piola(const TransverselyIsotropic& law, const Eigen::Matrix3d& C) {
  const double J = std::sqrt(C.determinant());
  const Eigen::Matrix3d Cinv = C.inverse();
  const double b = std::pow(J, -2.0 / 3.0);
  const double I1 = C.trace();
  const double I4 = law.fibre.dot(C * law.fibre);
  const Eigen::Matrix3d A = law.fibre * law.fibre.transpose();
  return law.mu * b * (Eigen::Matrix3d::Identity() - (I1 / 3.0) * Cinv) +
         2.0 * law.eta * (b * I4 - 1.0) * b * (A - (I4 / 3.0) * Cinv) + law.bulk * J * (J - 1.0) * Cinv;
}

TransverselyIsotropicLinearisation linearise(const TransverselyIsotropic&, const Eigen::Matrix3d& F) { return {F}; }

// The derivative of P (header) term by term, with t = tr(F⁻¹dF), dJ = J t, db = −2/3 b t,
// dF⁻ᵀ = −F⁻ᵀ dFᵀ F⁻ᵀ, dI₁ = 2 F:dF, dI₄ = 2 (F a)·(dF a).
Eigen::Matrix3d first_piola_increment(const TransverselyIsotropic& law, const TransverselyIsotropicLinearisation& at,
                                      const Eigen::Matrix3d& dF) {
  const Eigen::Matrix3d& F = at.F;
  const Eigen::Vector3d& a = law.fibre;
  const IsochoricIncrement k(F, dF);
  const double b = k.a, db = k.da;
  const Eigen::Matrix3d &FinvT = k.FinvT, &dFinvT = k.dFinvT;
  const double I1 = F.squaredNorm(), dI1 = 2.0 * (F.array() * dF.array()).sum();
  const Eigen::Vector3d Fa = F * a, dFa = dF * a;
  const double I4 = Fa.squaredNorm(), dI4 = 2.0 * Fa.dot(dFa);
  const double d4 = b * I4 - 1.0, dd4 = db * I4 + b * dI4;
  const Eigen::Matrix3d matrix = law.mu * (db * (F - (I1 / 3.0) * FinvT) + b * (dF - (dI1 / 3.0) * FinvT - (I1 / 3.0) * dFinvT));
  const Eigen::Matrix3d G = Fa * a.transpose() - (I4 / 3.0) * FinvT;
  const Eigen::Matrix3d dG = dFa * a.transpose() - (dI4 / 3.0) * FinvT - (I4 / 3.0) * dFinvT;
  const Eigen::Matrix3d fibre = 2.0 * law.eta * ((dd4 * b + d4 * db) * G + d4 * b * dG);
  return matrix + fibre + k.volumetric(law.bulk);
}

double volumetric_modulus(const TransverselyIsotropic& law) { return law.bulk; }

TransverselyIsotropic isochoric_part(const TransverselyIsotropic& law) {
  TransverselyIsotropic iso = law;
  iso.bulk = 0.0;
  return iso;
}

}  // namespace softsim::material
