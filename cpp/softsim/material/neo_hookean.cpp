#include "softsim/material/neo_hookean.hpp"

#include <cmath>

#include <Eigen/Dense>

namespace softsim::material {

std::string form_name(NeoHookeanForm form) {
  return form == NeoHookeanForm::paper ? "neo_hookean_paper" : "neo_hookean_decoupled";
}

std::string law_name(const NeoHookean& law) { return form_name(law.form); }

NeoHookean NeoHookean::from(NeoHookeanForm form, const ElasticParameters& p) {
  const LameParameters l = lame_parameters(p);
  NeoHookean law;
  law.form = form;
  law.mu = l.mu;
  law.lambda = l.lambda;
  law.bulk = bulk_modulus(p);
  return law;
}

double strain_energy_density(const NeoHookean& law, const Eigen::Matrix3d& F) {
  const double J = F.determinant();
  const double I1 = F.squaredNorm();
  if (law.form == NeoHookeanForm::paper)
    return 0.5 * law.mu * (I1 - 3.0) - law.mu * std::log(J) + 0.5 * law.lambda * (J - 1.0) * (J - 1.0);
  const double I1bar = std::pow(J, -2.0 / 3.0) * I1;
  return law.c10() * (I1bar - 3.0) + 0.5 * law.bulk * (J - 1.0) * (J - 1.0);  // (J − 1)²/D1
}

Eigen::Matrix3d first_piola(const NeoHookean& law, const Eigen::Matrix3d& F) {
  const double J = F.determinant();
  const Eigen::Matrix3d FinvT = F.inverse().transpose();
  if (law.form == NeoHookeanForm::paper)
    return law.mu * (F - FinvT) + law.lambda * J * (J - 1.0) * FinvT;  // F S with S of 000 eq. 14
  const double a = std::pow(J, -2.0 / 3.0);
  const double I1 = F.squaredNorm();
  return law.mu * a * (F - (I1 / 3.0) * FinvT) + law.bulk * J * (J - 1.0) * FinvT;
}

Eigen::Matrix3d second_piola(const NeoHookean& law, const Eigen::Matrix3d& C) {
  const double J = std::sqrt(C.determinant());
  const Eigen::Matrix3d Cinv = C.inverse();
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  if (law.form == NeoHookeanForm::paper)
    return law.mu * (I - Cinv) + law.lambda * J * (J - 1.0) * Cinv;  // 000 eq. 14
  const double a = std::pow(J, -2.0 / 3.0);
  return law.mu * a * (I - (C.trace() / 3.0) * Cinv) + law.bulk * J * (J - 1.0) * Cinv;
}

Eigen::Matrix3d first_piola_increment(const NeoHookean& law, const Eigen::Matrix3d& F,
                                      const Eigen::Matrix3d& dF) {
  return first_piola_increment(law, linearise(law, F), dF);
}

NeoHookeanLinearisation linearise(const NeoHookean& law, const Eigen::Matrix3d& F) {
  NeoHookeanLinearisation at;
  at.F = F;
  if (law.form == NeoHookeanForm::decoupled) at.a = std::pow(F.determinant(), -2.0 / 3.0);
  return at;
}

Eigen::Matrix3d first_piola_increment(const NeoHookean& law, const NeoHookeanLinearisation& at,
                                      const Eigen::Matrix3d& dF) {
  const Eigen::Matrix3d& F = at.F;
  const double J = F.determinant();
  const Eigen::Matrix3d Finv = F.inverse();
  const Eigen::Matrix3d FinvT = Finv.transpose();
  const double trFinvdF = (Finv * dF).trace();
  const double dJ = J * trFinvdF;
  const Eigen::Matrix3d dFinvT = -FinvT * dF.transpose() * FinvT;
  if (law.form == NeoHookeanForm::paper) {
    // P = μ F + g(J) F⁻ᵀ with g = λ J (J − 1) − μ.
    const double g = law.lambda * J * (J - 1.0) - law.mu;
    const double dg = law.lambda * (2.0 * J - 1.0) * dJ;
    return law.mu * dF + dg * FinvT + g * dFinvT;
  }
  // P = μ a F + h F⁻ᵀ with a = J^(−2/3), h = −μ a I₁/3 + K J (J − 1).
  const double a = at.a;
  const double da = -2.0 / 3.0 * a * trFinvdF;
  const double I1 = F.squaredNorm();
  const double dI1 = 2.0 * (F.array() * dF.array()).sum();
  const double h = -law.mu * a * I1 / 3.0 + law.bulk * J * (J - 1.0);
  const double dh = -law.mu / 3.0 * (da * I1 + a * dI1) + law.bulk * (2.0 * J - 1.0) * dJ;
  return law.mu * (da * F + a * dF) + dh * FinvT + h * dFinvT;
}

double volumetric_modulus(const NeoHookean& law) {
  return law.form == NeoHookeanForm::paper ? law.lambda : law.bulk;
}

NeoHookean isochoric_part(const NeoHookean& law) {
  NeoHookean iso = law;
  iso.lambda = 0.0;
  iso.bulk = 0.0;
  return iso;
}

}  // namespace softsim::material
