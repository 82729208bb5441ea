#include "softsim/meshless/gauss_legendre.hpp"

#include <cmath>
#include <stdexcept>

namespace softsim::meshless {

GaussRule gauss_legendre(int n) {
  if (n < 1 || n > 32) throw std::invalid_argument("gauss_legendre: order must lie in [1, 32]");
  GaussRule rule;
  rule.points.resize(n);
  rule.weights.resize(n);
  const double pi = std::acos(-1.0);
  // P_n(x) by the three-term recurrence, and P_n'(x) = n (x P_n - P_{n-1}) / (x² - 1).
  struct Legendre {
    double value, derivative;
  };
  const auto legendre = [n](double x) {
    double p0 = 1, p1 = x;
    for (int k = 2; k <= n; ++k) {
      const double pk = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
      p0 = p1;
      p1 = pk;
    }
    return Legendre{p1, n * (x * p1 - p0) / (x * x - 1)};
  };
  // Newton iteration on P_n from the Chebyshev-like initial guess; roots are symmetric.
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));
    for (int iter = 0; iter < 100; ++iter) {
      const Legendre p = legendre(x);
      const double dx = p.value / p.derivative;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    // Recompute the derivative at the converged root for the weight.
    const double dp = legendre(x).derivative;
    const double w = 2.0 / ((1 - x * x) * dp * dp);
    rule.points[i] = -x;
    rule.points[n - 1 - i] = x;
    rule.weights[i] = w;
    rule.weights[n - 1 - i] = w;
  }
  if (n % 2 == 1) rule.points[n / 2] = 0.0;
  return rule;
}

}  // namespace softsim::meshless
