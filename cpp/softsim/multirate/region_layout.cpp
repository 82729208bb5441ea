#include "softsim/multirate/region_layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "softsim/io/errors.hpp"

namespace softsim::multirate {

std::vector<int> contact_distance_order(const ReducedSystem& system, int contact_free_node) {
  const int n = system.num_free_nodes();
  if (contact_free_node < 0 || contact_free_node >= n) throw InputError("regions: contact node is not a free node");
  std::vector<int> hops(n, std::numeric_limits<int>::max());
  std::queue<int> queue;
  hops[contact_free_node] = 0;
  queue.push(contact_free_node);
  while (!queue.empty()) {
    const int a = queue.front();
    queue.pop();
    for (int b : system.neighbours[a])
      if (hops[b] == std::numeric_limits<int>::max()) {
        hops[b] = hops[a] + 1;
        queue.push(b);
      }
  }
  std::vector<double> dist(n);
  for (int a = 0; a < n; ++a) dist[a] = (system.positions[a] - system.positions[contact_free_node]).norm();
  std::vector<int> order(n);
  for (int a = 0; a < n; ++a) order[a] = a;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    if (hops[a] != hops[b]) return hops[a] < hops[b];
    if (dist[a] != dist[b]) return dist[a] < dist[b];
    return a < b;
  });
  return order;
}

RegionBorders::RegionBorders(int free_nodes, int primary_nodes) : free_nodes_(free_nodes), bounds_{primary_nodes} {}

int linear_primary_size(const PrimarySizePolicy& policy, double deformation) {
  const double target = std::ceil(policy.gradient * deformation / policy.scale);
  if (!(target > policy.min_nodes)) return policy.min_nodes;  // also catches NaN
  if (target >= policy.max_nodes) return policy.max_nodes;
  return static_cast<int>(target);
}

SlidingMax::SlidingMax(int window)
    : window_(std::max(1, window)), steps_(static_cast<std::size_t>(window_) + 1), values_(steps_.size()) {}

void SlidingMax::reset() { head_ = size_ = 0; }

int SlidingMax::push(long step, int value) {
  const int cap = static_cast<int>(steps_.size());
  // Drop smaller values from the back: they can never be the maximum again.
  while (size_ > 0 && values_[(head_ + size_ - 1) % cap] <= value) --size_;
  steps_[(head_ + size_) % cap] = step;
  values_[(head_ + size_) % cap] = value;
  ++size_;
  // Drop the front once it has left the window.
  while (steps_[head_] <= step - window_) {
    head_ = (head_ + 1) % cap;
    --size_;
  }
  return values_[head_];
}

}  // namespace softsim::multirate
