#include "softsim/meshless/background_cells.hpp"

#include <stdexcept>

#include "softsim/meshless/gauss_legendre.hpp"

namespace softsim::meshless {

QuadraturePoints box_quadrature(const Eigen::Vector3d& origin, const Eigen::Vector3d& size,
                                const std::array<int, 3>& cells, int order) {
  for (int a = 0; a < 3; ++a)
    if (cells[a] < 1 || !(size[a] > 0)) throw std::invalid_argument("box_quadrature: empty box");
  const GaussRule rule = gauss_legendre(order);
  const Eigen::Vector3d h(size.x() / cells[0], size.y() / cells[1], size.z() / cells[2]);
  const double jacobian = h.prod() / 8.0;  // [-1, 1]³ -> one cell
  QuadraturePoints q;
  const std::size_t total = static_cast<std::size_t>(cells[0]) * cells[1] * cells[2] * order * order * order;
  q.points.reserve(total);
  q.weights.reserve(total);
  for (int ck = 0; ck < cells[2]; ++ck)
    for (int cj = 0; cj < cells[1]; ++cj)
      for (int ci = 0; ci < cells[0]; ++ci) {
        const Eigen::Vector3d lo = origin + Eigen::Vector3d(ci * h.x(), cj * h.y(), ck * h.z());
        for (int k = 0; k < order; ++k)
          for (int j = 0; j < order; ++j)
            for (int i = 0; i < order; ++i) {
              const Eigen::Vector3d xi(rule.points[i], rule.points[j], rule.points[k]);
              q.points.push_back(lo + (0.5 * (xi.array() + 1.0) * h.array()).matrix());
              q.weights.push_back(rule.weights[i] * rule.weights[j] * rule.weights[k] * jacobian);
            }
      }
  return q;
}

}  // namespace softsim::meshless
