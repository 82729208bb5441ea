#pragma once
// Support-domain queries (002 §2.3: "a support domain of a certain size is centered [at each
// Gauss point] to include some nodes"): nodes within a radius, or the k nearest nodes.
// A uniform bucket grid keeps each query local; results are deterministic (sorted).
#include <vector>

#include <Eigen/Core>

namespace softsim::meshless {

class NodeSearch {
 public:
  // cell: bucket edge length (m); a value near the typical query radius is best.
  NodeSearch(const std::vector<Eigen::Vector3d>& nodes, double cell);

  // Indices of nodes with |x_i - x| <= radius, ascending.
  void within(const Eigen::Vector3d& x, double radius, std::vector<int>& out) const;
  // The k nearest nodes, ordered by distance (ties by index). Requires k <= node count.
  void nearest(const Eigen::Vector3d& x, int k, std::vector<int>& out) const;

  int size() const { return static_cast<int>(nodes_.size()); }

 private:
  Eigen::Vector3i cell_of(const Eigen::Vector3d& x) const;

  const std::vector<Eigen::Vector3d>& nodes_;
  double cell_;
  Eigen::Vector3d lo_;
  Eigen::Vector3i dims_;
  std::vector<int> start_;   // bucket b holds order_[start_[b] .. start_[b+1])
  std::vector<int> order_;
};

}  // namespace softsim::meshless
