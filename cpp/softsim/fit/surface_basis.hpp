#pragma once
// Surface polynomials of the surface-node coordinates (002 eq. 44).
//
//   separable (the paper): u(x, y) = p1 + Σ_{i=1..a} p φ_i(sx) + Σ_{j=1..b} p φ_j(sy), no cross terms
//   bivariate (beyond the paper): u(x, y) = Σ_{i+j<=n} p_ij φ_i(sx) φ_j(sy)
//   trivariate (beyond the paper): u(x, y, z) = Σ_{i+j+k<=n, k<=m} p_ijk φ_i(sx) φ_j(sy) φ_k(sz)
//   zero: the component is neglected (the paper's "Δy = 0" under a force along X, Table 1)
// with sx, sy, sz the coordinates scaled onto [-1, 1] and φ the polynomial basis.
//
// The paper's plate is a flat top face, so x and y name every node. A closed organ surface has
// an upper and a lower node over the same (x, y), which no polynomial of x and y can tell apart:
// the trivariate surface adds z. Its z power is capped at m (z_degree, normally n): on nodes that
// all lie in one plane z = const every φ_k(sz) is a constant, the terms with k > 0 would repeat
// those with k = 0 and make the design singular, so there m = 0 and the surface is exactly the
// bivariate one of the same degree (same terms, same order, same coefficients).
#include <array>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "softsim/fit/basis.hpp"

namespace softsim::fit {

enum class SurfaceModel { zero, separable, bivariate, trivariate };

const char* to_string(SurfaceModel model);

struct SurfaceTerms {
  SurfaceModel model = SurfaceModel::zero;
  int order_x = 0;  // a (separable)
  int order_y = 0;  // b (separable)
  int degree = 0;   // n (bivariate, trivariate)
  int z_degree = 0; // m (trivariate): highest power of z
  // Term t is φ_i(sx) φ_j(sy) φ_k(sz) with (i, j, k) = terms[t]. Separable order: 1, x..x^a,
  // y..y^b (the paper's p1, p2, ..., p_h); bivariate: by total degree, then by decreasing x
  // power; trivariate: by total degree, then by increasing z power, then by decreasing x power
  // (so that with m = 0 its terms are the bivariate ones in the same order).
  std::vector<std::array<int, 3>> terms;

  static SurfaceTerms zero();
  static SurfaceTerms separable(int order_x, int order_y);
  static SurfaceTerms bivariate(int degree);
  static SurfaceTerms trivariate(int degree, int z_degree);

  int size() const { return static_cast<int>(terms.size()); }
  int max_order() const;  // highest single-variable order used
  bool uses_z() const;    // some term has a power of z
  std::string label() const;  // "(a, b)", "n = 4", "n = 4 (xyz)", "n = 4 (xyz, z^0)" or "zero"
};

// The scaled coordinates in which surfaces are expanded.
struct SurfaceFrame {
  Basis basis = Basis::legendre;
  AffineScale x;
  AffineScale y;
  AffineScale z;  // used by trivariate surfaces only
};

// Design matrix (rows of `xy` × terms) at the node coordinates xy (columns 0 and 1 used; column 2
// too when the terms use z).
Eigen::MatrixXd surface_design(const SurfaceTerms& terms, const SurfaceFrame& frame,
                               const Eigen::MatrixXd& xy);

// Whether the nodes (rows × 3) span z: false when they all lie in one plane z = const (a z range
// below 1e-9 of their x–y extent), where a trivariate surface drops its z terms (z_degree 0).
bool nodes_span_z(const Eigen::MatrixXd& nodes);

}  // namespace softsim::fit
