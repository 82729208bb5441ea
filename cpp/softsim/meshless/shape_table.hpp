#pragma once
// Shape functions and their gradients at every Gauss point, precomputed once (the setup
// phase of 002 §2.3): support nodes, φ and ∇φ stored contiguously (CSR-like) so that the
// assembly loops read them without any further search or solve.
#include <vector>

#include <Eigen/Core>

#include "softsim/meshless/background_cells.hpp"
#include "softsim/meshless/rpim_shape.hpp"

namespace softsim::meshless {

struct SupportRule {
  enum class Kind { radius, nearest };
  Kind kind = Kind::radius;
  double radius = 0.0;  // m (kind radius)
  int count = 0;        // k (kind nearest)
};

struct ShapeTable {
  std::vector<Eigen::Vector3d> points;  // Gauss points (m)
  std::vector<double> weights;          // quadrature weights (m³)
  std::vector<int> offsets;             // point g owns entries [offsets[g], offsets[g+1])
  std::vector<int> nodes;               // support node of each entry
  std::vector<double> phi;              // φ of each entry
  std::vector<double> dphi;             // ∇φ of each entry, 3 per entry (1/m)
  std::vector<double> moment_condition; // per point

  int num_points() const { return static_cast<int>(points.size()); }
  int support_size(int g) const { return offsets[g + 1] - offsets[g]; }
};

// Summary statistics of the per-point support sizes and moment-matrix conditions.
struct ShapeTableStats {
  int points = 0;
  int min_support = 0, max_support = 0;
  double mean_support = 0;
  double min_condition = 0, median_condition = 0, max_condition = 0;
  // Consistency of the shape functions at the Gauss points: max |Σφ - 1| (partition of unity),
  // max |Σφ_I x_I - x| / h and max |Σ ∇φ_I x_Iᵀ - I| (linear reproduction of values and
  // gradients). Round-off small with linear augmentation; O(1e-4..1e-2) for pure MQ.
  double partition_error = 0;
  double linear_error = 0;
  double gradient_error = 0;
};
ShapeTableStats shape_table_stats(const ShapeTable& table, const std::vector<Eigen::Vector3d>& nodes,
                                  double spacing);

// Builds the table. Throws NumericalError (naming the point and the condition number) when
// a support is empty or a moment matrix is singular; with several failing points the one
// with the lowest index is reported, whatever the thread count.
ShapeTable build_shape_table(const std::vector<Eigen::Vector3d>& nodes, const QuadraturePoints& quadrature,
                             const SupportRule& support, const RbfParams& rbf);

}  // namespace softsim::meshless
