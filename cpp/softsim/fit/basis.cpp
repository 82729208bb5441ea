#include "softsim/fit/basis.hpp"

#include <cmath>

namespace softsim::fit {

namespace {

// P_{n+1}(t) from P_n(t) = p and P_{n-1}(t) = p_prev (Bonnet's recurrence).
double legendre_next(int n, double t, double p, double p_prev) {
  return ((2 * n + 1) * t * p - n * p_prev) / (n + 1);
}

}  // namespace

const char* to_string(Basis basis) { return basis == Basis::legendre ? "legendre" : "monomial"; }

AffineScale AffineScale::from_range(double lo, double hi) {
  AffineScale s;
  s.center = 0.5 * (lo + hi);
  const double half = 0.5 * (hi - lo);
  s.half_width = half > 0.0 ? half : 1.0;
  return s;
}

void evaluate_basis(Basis basis, int order, double t, double* out) {
  out[0] = 1.0;
  if (order < 1) return;
  out[1] = t;
  for (int n = 1; n < order; ++n) {
    if (basis == Basis::legendre)
      out[n + 1] = legendre_next(n, t, out[n], out[n - 1]);
    else
      out[n + 1] = out[n] * t;
  }
}

double Polynomial1D::operator()(double x) const {
  const int n = order();
  if (n < 0) return 0.0;
  const double t = scale.to_unit(x);
  if (basis == Basis::monomial) {
    double acc = coefficients[n];
    for (int k = n - 1; k >= 0; --k) acc = acc * t + coefficients[k];
    return acc;
  }
  double p_prev = 1.0, p = t;
  double acc = coefficients[0];
  if (n >= 1) acc += coefficients[1] * t;
  for (int k = 1; k < n; ++k) {
    const double p_next = legendre_next(k, t, p, p_prev);
    p_prev = p;
    p = p_next;
    acc += coefficients[k + 1] * p;
  }
  return acc;
}

Eigen::MatrixXd basis_to_monomial(Basis basis, const AffineScale& scale, int order, double origin,
                                  double unit) {
  const int m = order + 1;
  // L(k, n): coefficient of t^k in phi_n(t).
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(m, m);
  L(0, 0) = 1.0;
  if (m > 1) L(1, 1) = 1.0;
  for (int n = 1; n + 1 < m; ++n) {
    if (basis == Basis::legendre) {
      for (int k = 0; k < m; ++k) {
        double v = -n * L(k, n - 1);
        if (k > 0) v += (2 * n + 1) * L(k - 1, n);
        L(k, n + 1) = v / (n + 1);
      }
    } else {
      L(n + 1, n + 1) = 1.0;
    }
  }
  // t = alpha u + beta with x = origin + u / unit.
  const double alpha = 1.0 / (unit * scale.half_width);
  const double beta = (origin - scale.center) / scale.half_width;
  // S(j, k): coefficient of u^j in t^k = sum_j C(k, j) alpha^j beta^(k-j) u^j.
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(m, m);
  for (int k = 0; k < m; ++k) {
    double binom = 1.0;
    for (int j = 0; j <= k; ++j) {
      S(j, k) = binom * std::pow(alpha, j) * std::pow(beta, k - j);
      binom = binom * (k - j) / (j + 1);
    }
  }
  return S * L;
}

}  // namespace softsim::fit
