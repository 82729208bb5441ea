#include "softsim/material/stable_neo_hookean.hpp"

#include <Eigen/LU>

namespace softsim::material {

StableNeoHookean StableNeoHookean::from(const ElasticParameters& p) {
  const LameParameters l = lame_parameters(p);
  // Smith et al. 2018 §3.4: the small-strain tangent of W is 3μ/4 (H + Hᵀ) + (λ − 5μ/8) tr(H) I.
  return StableNeoHookean{4.0 / 3.0 * l.mu, l.lambda + 5.0 / 6.0 * l.mu};
}

std::string law_name(const StableNeoHookean&) { return "stable_neo_hookean"; }

ElasticParameters small_strain_parameters(const StableNeoHookean& law, double density) {
  return from_lame(0.75 * law.mu, law.lambda - 0.625 * law.mu, density);
}

double strain_energy_density(const StableNeoHookean& law, const Eigen::Matrix3d& F) {
  const double J = F.determinant();
  const double Ic = F.squaredNorm();
  return 0.5 * law.mu * (Ic - 3.0) - 0.5 * law.mu * std::log((Ic + 1.0) / 4.0) - 0.75 * law.mu * (J - 1.0) +
         0.5 * law.lambda * (J - 1.0) * (J - 1.0);
}

Eigen::Matrix3d second_piola(const StableNeoHookean& law, const Eigen::Matrix3d& C) {
  const double J = std::sqrt(C.determinant());
  const double Ic = C.trace();
  return law.mu * (1.0 - 1.0 / (Ic + 1.0)) * Eigen::Matrix3d::Identity() +
         (law.lambda * (J - 1.0) - 0.75 * law.mu) * J * C.inverse();
}

StableNeoHookeanLinearisation linearise(const StableNeoHookean&, const Eigen::Matrix3d& F) {
  StableNeoHookeanLinearisation at;
  at.F = F;
  at.cof = cofactor(F);
  at.J = F.col(0).dot(at.cof.col(0));
  at.Ic = F.squaredNorm();
  return at;
}

Eigen::Matrix3d first_piola_increment(const StableNeoHookean& law, const StableNeoHookeanLinearisation& at,
                                      const Eigen::Matrix3d& dF) {
  const Eigen::Matrix3d& F = at.F;
  const double q = 1.0 / (at.Ic + 1.0);
  const double FdF = (F.array() * dF.array()).sum();
  const double cofdF = (at.cof.array() * dF.array()).sum();  // dJ
  Eigen::Matrix3d dcof;
  for (int j = 0; j < 3; ++j) {
    const int a = (j + 1) % 3, b = (j + 2) % 3;
    dcof.col(j) = dF.col(a).cross(F.col(b)) + F.col(a).cross(dF.col(b));
  }
  return law.mu * (1.0 - q) * dF + 2.0 * law.mu * q * q * FdF * F + law.lambda * cofdF * at.cof +
         (law.lambda * (at.J - 1.0) - 0.75 * law.mu) * dcof;
}

double volumetric_modulus(const StableNeoHookean& law) { return law.lambda; }

StableNeoHookean isochoric_part(const StableNeoHookean& law) {
  StableNeoHookean rest = law;
  rest.lambda = 0.0;
  return rest;
}

}  // namespace softsim::material
