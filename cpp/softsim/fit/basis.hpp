#pragma once
// Polynomials of one scaled variable: the building block of every relation of 002 §3.
//
// A raw variable x (a force in N, a coordinate or a displacement in m) is first mapped onto
// the unit interval, t = (x - center) / half_width, and the polynomial is expanded in a basis
// of t (Legendre by default). On [-1, 1] the Legendre basis keeps the normal equations well
// conditioned up to high orders, where raw monomials of millimetre-sized SI numbers would not.
#include <string>

#include <Eigen/Dense>

namespace softsim::fit {

enum class Basis { legendre, monomial };

const char* to_string(Basis basis);

// Highest polynomial order any relation may use (fixed-size scratch arrays in playback).
inline constexpr int kMaxOrder = 16;

// t = (x - center) / half_width.
struct AffineScale {
  double center = 0.0;
  double half_width = 1.0;

  double to_unit(double x) const { return (x - center) / half_width; }
  // Maps [lo, hi] onto [-1, 1]. A degenerate range (lo == hi) keeps half_width = 1: the
  // design built on it is then rank deficient and refused as ill-conditioned.
  static AffineScale from_range(double lo, double hi);
};

// Basis functions 0..order at t, written to out[0..order]. No allocation.
void evaluate_basis(Basis basis, int order, double t, double* out);

// p(x) = sum_k coefficients[k] * phi_k(scale.to_unit(x)).
struct Polynomial1D {
  Basis basis = Basis::legendre;
  AffineScale scale;
  Eigen::VectorXd coefficients;

  int order() const { return static_cast<int>(coefficients.size()) - 1; }
  double operator()(double x) const;  // no allocation
};

// Matrix T with m = T c: the monomial coefficients m_k of sum_k m_k u^k equal to the basis
// expansion sum_k c_k phi_k(t), where the raw variable is x = origin + u / unit
// (u measured from `origin` in units of 1/unit, e.g. unit = 1000 for millimetres).
Eigen::MatrixXd basis_to_monomial(Basis basis, const AffineScale& scale, int order, double origin,
                                  double unit);

}  // namespace softsim::fit
