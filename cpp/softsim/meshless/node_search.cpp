#include "softsim/meshless/node_search.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace softsim::meshless {

NodeSearch::NodeSearch(const std::vector<Eigen::Vector3d>& nodes, double cell)
    : nodes_(nodes), cell_(cell) {
  if (nodes.empty()) throw std::invalid_argument("NodeSearch: no nodes");
  if (!(cell > 0)) throw std::invalid_argument("NodeSearch: cell size must be positive");
  Eigen::Vector3d lo = nodes[0], hi = nodes[0];
  for (const auto& p : nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  lo_ = lo;
  for (int a = 0; a < 3; ++a)
    dims_[a] = std::max(1, std::min(1024, static_cast<int>(std::floor((hi[a] - lo[a]) / cell_)) + 1));
  const int buckets = dims_.prod();
  std::vector<int> bucket_of(nodes.size());
  start_.assign(buckets + 1, 0);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Vector3i c = cell_of(nodes[i]);
    bucket_of[i] = c.x() + dims_.x() * (c.y() + dims_.y() * c.z());
    ++start_[bucket_of[i] + 1];
  }
  for (int b = 0; b < buckets; ++b) start_[b + 1] += start_[b];
  order_.resize(nodes.size());
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < nodes.size(); ++i) order_[fill[bucket_of[i]]++] = static_cast<int>(i);
}

Eigen::Vector3i NodeSearch::cell_of(const Eigen::Vector3d& x) const {
  Eigen::Vector3i c;
  for (int a = 0; a < 3; ++a) {
    const int v = static_cast<int>(std::floor((x[a] - lo_[a]) / cell_));
    c[a] = std::clamp(v, 0, dims_[a] - 1);
  }
  return c;
}

void NodeSearch::within(const Eigen::Vector3d& x, double radius, std::vector<int>& out) const {
  out.clear();
  const Eigen::Vector3i a = cell_of(x - Eigen::Vector3d::Constant(radius));
  const Eigen::Vector3i b = cell_of(x + Eigen::Vector3d::Constant(radius));
  const double r2 = radius * radius;
  for (int k = a.z(); k <= b.z(); ++k)
    for (int j = a.y(); j <= b.y(); ++j)
      for (int i = a.x(); i <= b.x(); ++i) {
        const int bucket = i + dims_.x() * (j + dims_.y() * k);
        for (int s = start_[bucket]; s < start_[bucket + 1]; ++s) {
          const int n = order_[s];
          if ((nodes_[n] - x).squaredNorm() <= r2) out.push_back(n);
        }
      }
  std::sort(out.begin(), out.end());
}

void NodeSearch::nearest(const Eigen::Vector3d& x, int k, std::vector<int>& out) const {
  if (k < 1 || k > size()) throw std::invalid_argument("NodeSearch::nearest: k out of range");
  // Grow a ball until it holds k nodes, then keep the k closest. Distances are computed once
  // and stored: recomputing them inside the comparator may round differently between calls
  // (fused multiply-add), which breaks the strict weak ordering std::sort relies on.
  double radius = cell_;
  std::vector<int> found;
  for (;;) {
    within(x, radius, found);
    if (static_cast<int>(found.size()) >= k) break;
    radius *= 1.5;
  }
  std::vector<std::pair<double, int>> ranked(found.size());
  for (std::size_t a = 0; a < found.size(); ++a) ranked[a] = {(nodes_[found[a]] - x).squaredNorm(), found[a]};
  std::partial_sort(ranked.begin(), ranked.begin() + k, ranked.end());
  out.resize(k);
  for (int a = 0; a < k; ++a) out[a] = ranked[a].second;
}

}  // namespace softsim::meshless
