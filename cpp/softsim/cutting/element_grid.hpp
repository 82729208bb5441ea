#pragma once
// A uniform grid over the reference bounding boxes of a mesh's elements, so that a blade sweep
// tests only the elements near it instead of scanning the whole mesh (a haptic blade sweeps
// every frame). Built once per mesh; a query in the current geometry X + u widens the sweep's
// box by the largest nodal displacement, which bounds how far any element has moved from its
// reference box, so no crossed element is ever missed.
#include <vector>

#include <Eigen/Core>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::cutting {

class ElementGrid {
 public:
  explicit ElementGrid(const mesh::TetMesh& mesh);

  // The elements whose reference box overlaps [lo, hi], ascending, into `out` (replaced).
  // Not thread-safe: one query at a time (it marks elements seen in a member array).
  void candidates(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::vector<int>& out) const;

  int num_cells() const { return dims_[0] * dims_[1] * dims_[2]; }

 private:
  Eigen::Vector3d origin_;
  Eigen::Vector3d cell_size_;
  int dims_[3] = {1, 1, 1};
  std::vector<int> cell_begin_, cell_elements_;  // CSR: the elements binned in each cell
  mutable std::vector<unsigned> seen_;           // per element: the query that last took it
  mutable unsigned query_ = 0;
};

// The largest |u_a| over the nodes (0 for u == null).
double largest_displacement(const double* u, int num_nodes);

}  // namespace softsim::cutting
