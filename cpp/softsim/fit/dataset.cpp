#include "softsim/fit/dataset.hpp"

#include <algorithm>
#include <cmath>

namespace softsim::fit {

std::vector<double> loaded_displacements(const Dataset& data, int component) {
  std::vector<double> out;
  out.reserve(data.cases.size());
  for (const auto& c : data.cases) out.push_back(c.displacement(data.loaded_node, component));
  return out;
}

std::vector<double> force_components(const Dataset& data, int direction) {
  std::vector<double> out;
  out.reserve(data.cases.size());
  for (const auto& c : data.cases) out.push_back(c.force[direction]);
  return out;
}

double off_axis_fraction(const Dataset& data, int direction) {
  double largest = 0.0, off = 0.0;
  for (const auto& c : data.cases) {
    largest = std::max(largest, c.force.norm());
    for (int a = 0; a < 3; ++a)
      if (a != direction) off = std::max(off, std::abs(c.force[a]));
  }
  return largest > 0.0 ? off / largest : 0.0;
}

bool same_surface(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  if (a.rows() == 0) return true;
  const double extent = (a.colwise().maxCoeff() - a.colwise().minCoeff()).norm();
  return (a - b).cwiseAbs().maxCoeff() <= 1e-9 * std::max(extent, 1e-300);
}

}  // namespace softsim::fit
