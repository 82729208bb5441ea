#pragma once
// Surface polynomials of the top-node coordinates (002 eq. 44).
//
//   separable (the paper): u(x, y) = p1 + Σ_{i=1..a} p φ_i(sx) + Σ_{j=1..b} p φ_j(sy), no cross terms
//   bivariate (beyond the paper): u(x, y) = Σ_{i+j<=n} p_ij φ_i(sx) φ_j(sy)
//   zero: the component is neglected (the paper's "Δy = 0" under a force along X, Table 1)
// with sx, sy the coordinates scaled onto [-1, 1] and φ the polynomial basis.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "softsim/fit/basis.hpp"

namespace softsim::fit {

enum class SurfaceModel { zero, separable, bivariate };

const char* to_string(SurfaceModel model);

struct SurfaceTerms {
  SurfaceModel model = SurfaceModel::zero;
  int order_x = 0;  // a (separable)
  int order_y = 0;  // b (separable)
  int degree = 0;   // n (bivariate)
  // Term k is φ_i(sx) φ_j(sy) with (i, j) = terms[k]. Separable order: 1, x..x^a, y..y^b
  // (the paper's p1, p2, ..., p_h); bivariate: by total degree, then by decreasing x power.
  std::vector<std::array<int, 2>> terms;

  static SurfaceTerms zero();
  static SurfaceTerms separable(int order_x, int order_y);
  static SurfaceTerms bivariate(int degree);

  int size() const { return static_cast<int>(terms.size()); }
  int max_order() const;  // highest single-variable order used
  std::string label() const;  // "(a, b)", "n = 4" or "zero"
};

// The scaled plane in which surfaces are expanded.
struct SurfaceFrame {
  Basis basis = Basis::legendre;
  AffineScale x;
  AffineScale y;
};

// Design matrix (rows of `xy` × terms) at the coordinates xy (columns 0 and 1 used).
Eigen::MatrixXd surface_design(const SurfaceTerms& terms, const SurfaceFrame& frame,
                               const Eigen::MatrixXd& xy);

}  // namespace softsim::fit
