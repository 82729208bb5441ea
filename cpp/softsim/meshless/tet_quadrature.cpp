#include "softsim/meshless/tet_quadrature.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace softsim::meshless {

bool is_tet_rule_size(int points) { return points == 1 || points == 4 || points == 5; }

TetRule tet_rule(int points) {
  TetRule r;
  if (points == 1) {
    r.barycentric = {{0.25, 0.25, 0.25, 0.25}};
    r.weights = {1.0};
    r.degree = 1;
  } else if (points == 4) {
    const double a = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0, b = (5.0 - std::sqrt(5.0)) / 20.0;
    r.barycentric = {{a, b, b, b}, {b, a, b, b}, {b, b, a, b}, {b, b, b, a}};
    r.weights = {0.25, 0.25, 0.25, 0.25};
    r.degree = 2;
  } else if (points == 5) {
    const double a = 0.5, b = 1.0 / 6.0;
    r.barycentric = {{0.25, 0.25, 0.25, 0.25}, {a, b, b, b}, {b, a, b, b}, {b, b, a, b}, {b, b, b, a}};
    r.weights = {-0.8, 0.45, 0.45, 0.45, 0.45};
    r.degree = 3;
  } else {
    throw std::invalid_argument("tet_rule: 1, 4 or 5 points, not " + std::to_string(points));
  }
  return r;
}

QuadraturePoints tet_quadrature(const mesh::TetMesh& mesh, const TetRule& rule) {
  QuadraturePoints q;
  const std::size_t total = mesh.tets.size() * rule.weights.size();
  q.points.reserve(total);
  q.weights.reserve(total);
  for (const auto& t : mesh.tets) {
    const double volume = std::abs(mesh::signed_volume(mesh, t));
    for (std::size_t p = 0; p < rule.weights.size(); ++p) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int c = 0; c < 4; ++c) x += rule.barycentric[p][c] * mesh.nodes[t[c]];
      q.points.push_back(x);
      q.weights.push_back(rule.weights[p] * volume);
    }
  }
  return q;
}

}  // namespace softsim::meshless
