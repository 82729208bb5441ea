#include "softsim/fit/surface_basis.hpp"

#include <algorithm>
#include <stdexcept>

namespace softsim::fit {

const char* to_string(SurfaceModel model) {
  switch (model) {
    case SurfaceModel::zero: return "zero";
    case SurfaceModel::separable: return "separable";
    case SurfaceModel::bivariate: return "bivariate";
    case SurfaceModel::trivariate: return "trivariate";
  }
  return "unknown";
}

SurfaceTerms SurfaceTerms::zero() { return SurfaceTerms{}; }

SurfaceTerms SurfaceTerms::separable(int order_x, int order_y) {
  SurfaceTerms s;
  s.model = SurfaceModel::separable;
  s.order_x = order_x;
  s.order_y = order_y;
  s.terms.push_back({0, 0, 0});
  for (int i = 1; i <= order_x; ++i) s.terms.push_back({i, 0, 0});
  for (int j = 1; j <= order_y; ++j) s.terms.push_back({0, j, 0});
  return s;
}

SurfaceTerms SurfaceTerms::bivariate(int degree) {
  SurfaceTerms s;
  s.model = SurfaceModel::bivariate;
  s.degree = degree;
  for (int d = 0; d <= degree; ++d)
    for (int i = d; i >= 0; --i) s.terms.push_back({i, d - i, 0});
  return s;
}

SurfaceTerms SurfaceTerms::trivariate(int degree, int z_degree) {
  SurfaceTerms s;
  s.model = SurfaceModel::trivariate;
  s.degree = degree;
  s.z_degree = std::min(z_degree, degree);
  for (int d = 0; d <= degree; ++d)
    for (int k = 0; k <= std::min(d, s.z_degree); ++k)
      for (int i = d - k; i >= 0; --i) s.terms.push_back({i, d - k - i, k});
  return s;
}

int SurfaceTerms::max_order() const {
  int m = 0;
  for (const auto& t : terms) m = std::max({m, t[0], t[1], t[2]});
  return m;
}

bool SurfaceTerms::uses_z() const {
  return std::any_of(terms.begin(), terms.end(), [](const auto& t) { return t[2] > 0; });
}

std::string SurfaceTerms::label() const {
  switch (model) {
    case SurfaceModel::zero: return "zero";
    case SurfaceModel::separable:
      return "(" + std::to_string(order_x) + ", " + std::to_string(order_y) + ")";
    case SurfaceModel::bivariate: return "n = " + std::to_string(degree);
    case SurfaceModel::trivariate:
      return "n = " + std::to_string(degree) +
             (z_degree < degree ? " (xyz, z^" + std::to_string(z_degree) + ")" : std::string(" (xyz)"));
  }
  return "";
}

Eigen::MatrixXd surface_design(const SurfaceTerms& terms, const SurfaceFrame& frame,
                               const Eigen::MatrixXd& xy) {
  const int n = static_cast<int>(xy.rows());
  const int order = terms.max_order();
  if (order > kMaxOrder) throw std::invalid_argument("surface_design: order above kMaxOrder");
  Eigen::MatrixXd design(n, terms.size());
  double px[kMaxOrder + 1];
  double py[kMaxOrder + 1];
  double pz[kMaxOrder + 1] = {1.0};  // φ_0 = 1 only, unless the terms use z
  const bool with_z = terms.uses_z();
  if (with_z && xy.cols() < 3) throw std::invalid_argument("surface_design: z terms need x, y, z columns");
  for (int r = 0; r < n; ++r) {
    evaluate_basis(frame.basis, order, frame.x.to_unit(xy(r, 0)), px);
    evaluate_basis(frame.basis, order, frame.y.to_unit(xy(r, 1)), py);
    if (with_z) evaluate_basis(frame.basis, order, frame.z.to_unit(xy(r, 2)), pz);
    // Multiplying by φ_0 = 1 is exact: the 2-D kinds stay bit for bit what they were.
    for (int k = 0; k < terms.size(); ++k) {
      const auto& t = terms.terms[k];
      design(r, k) = px[t[0]] * py[t[1]] * pz[t[2]];
    }
  }
  return design;
}

bool nodes_span_z(const Eigen::MatrixXd& nodes) {
  if (nodes.rows() == 0 || nodes.cols() < 3) return false;
  const double extent = std::max(nodes.col(0).maxCoeff() - nodes.col(0).minCoeff(),
                                 nodes.col(1).maxCoeff() - nodes.col(1).minCoeff());
  return nodes.col(2).maxCoeff() - nodes.col(2).minCoeff() > 1e-9 * extent;
}

}  // namespace softsim::fit
