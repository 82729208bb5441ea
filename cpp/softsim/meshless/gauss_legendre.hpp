#pragma once
// Gauss–Legendre rules on [-1, 1]: the quadrature of the background cells (002 §2.3:
// "Gaussian integral points are determined by Gauss–Legendre formula in each unit"), from GSL.
#include <vector>

namespace softsim::meshless {

struct GaussRule {
  std::vector<double> points;   // abscissae in (-1, 1), ascending
  std::vector<double> weights;  // positive, summing to 2
};

// An n-point rule (exact for polynomials of degree 2n - 1), 1 <= n <= 32.
GaussRule gauss_legendre(int n);

}  // namespace softsim::meshless
