#include "softsim/fit/surface_basis.hpp"

#include <algorithm>
#include <stdexcept>

namespace softsim::fit {

const char* to_string(SurfaceModel model) {
  switch (model) {
    case SurfaceModel::zero: return "zero";
    case SurfaceModel::separable: return "separable";
    case SurfaceModel::bivariate: return "bivariate";
  }
  return "unknown";
}

SurfaceTerms SurfaceTerms::zero() { return SurfaceTerms{}; }

SurfaceTerms SurfaceTerms::separable(int order_x, int order_y) {
  SurfaceTerms s;
  s.model = SurfaceModel::separable;
  s.order_x = order_x;
  s.order_y = order_y;
  s.terms.push_back({0, 0});
  for (int i = 1; i <= order_x; ++i) s.terms.push_back({i, 0});
  for (int j = 1; j <= order_y; ++j) s.terms.push_back({0, j});
  return s;
}

SurfaceTerms SurfaceTerms::bivariate(int degree) {
  SurfaceTerms s;
  s.model = SurfaceModel::bivariate;
  s.degree = degree;
  for (int d = 0; d <= degree; ++d)
    for (int i = d; i >= 0; --i) s.terms.push_back({i, d - i});
  return s;
}

int SurfaceTerms::max_order() const {
  int m = 0;
  for (const auto& t : terms) m = std::max({m, t[0], t[1]});
  return m;
}

std::string SurfaceTerms::label() const {
  switch (model) {
    case SurfaceModel::zero: return "zero";
    case SurfaceModel::separable:
      return "(" + std::to_string(order_x) + ", " + std::to_string(order_y) + ")";
    case SurfaceModel::bivariate: return "n = " + std::to_string(degree);
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
  for (int r = 0; r < n; ++r) {
    evaluate_basis(frame.basis, order, frame.x.to_unit(xy(r, 0)), px);
    evaluate_basis(frame.basis, order, frame.y.to_unit(xy(r, 1)), py);
    for (int k = 0; k < terms.size(); ++k) design(r, k) = px[terms.terms[k][0]] * py[terms.terms[k][1]];
  }
  return design;
}

}  // namespace softsim::fit
