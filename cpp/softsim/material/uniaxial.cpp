#include "softsim/material/uniaxial.hpp"

#include <cmath>
#include <stdexcept>

namespace softsim::material {

UniaxialSolution uniaxial_neo_hookean(const NeoHookean& law, double a) {
  if (!(a > 0)) throw std::invalid_argument("uniaxial: the axial stretch must be positive");
  UniaxialSolution sol;
  sol.axial_stretch = a;
  const double mu = law.mu;
  if (law.form == NeoHookeanForm::paper) {
    const double lam = law.lambda;
    double s = 1.0;
    if (lam != 0.0) {
      const double b = mu - lam * a;
      s = (-b + std::sqrt(b * b + 4.0 * lam * a * a * mu)) / (2.0 * lam * a * a);
    }
    const double t = std::sqrt(s);
    const double J = s * a;
    sol.lateral_stretch = t;
    sol.nominal_stress = mu * (a - 1.0 / a) + lam * J * (J - 1.0) / a;
    return sol;
  }
  const double K = law.bulk;
  auto lateral_residual = [&](double t) {
    const double J = t * t * a;
    return mu * std::pow(J, -2.0 / 3.0) * (t * t - a * a) / 3.0 + K * J * (J - 1.0);
  };
  double lo = 1e-4, hi = 1e4;
  if (!(lateral_residual(lo) < 0 && lateral_residual(hi) > 0))
    throw std::runtime_error("uniaxial: no bracket for the lateral stretch");
  for (int i = 0; i < 300 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (lateral_residual(mid) < 0 ? lo : hi) = mid;
  }
  const double t = 0.5 * (lo + hi);
  const double J = t * t * a;
  const double I1 = 2.0 * t * t + a * a;
  sol.lateral_stretch = t;
  sol.nominal_stress = mu * std::pow(J, -2.0 / 3.0) * (a - I1 / (3.0 * a)) + K * J * (J - 1.0) / a;
  return sol;
}

UniaxialSolution uniaxial_linear(const ElasticParameters& p, double a) {
  UniaxialSolution sol;
  sol.axial_stretch = a;
  sol.lateral_stretch = 1.0 - p.poisson_ratio * (a - 1.0);
  sol.nominal_stress = p.youngs_modulus * (a - 1.0);
  return sol;
}

}  // namespace softsim::material
