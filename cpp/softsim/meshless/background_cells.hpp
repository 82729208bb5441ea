#pragma once
// Background integration cells (002 §2.3 and §4.1: the plate is divided into 64 cells of
// 6 × 6 × 6 mm, each carrying a tensor-product Gauss–Legendre rule). The cells only carry
// quadrature; they are not elements and do not constrain the shape functions.
#include <array>
#include <vector>

#include <Eigen/Core>

namespace softsim::meshless {

struct QuadraturePoints {
  std::vector<Eigen::Vector3d> points;  // m
  std::vector<double> weights;          // m³ (sum = box volume)
};

// A box [origin, origin + size] split into cells[0] × cells[1] × cells[2] cells, each with an
// order³ Gauss rule. Points are ordered cell by cell (x fastest), then within a cell.
QuadraturePoints box_quadrature(const Eigen::Vector3d& origin, const Eigen::Vector3d& size,
                                const std::array<int, 3>& cells, int order);

}  // namespace softsim::meshless
