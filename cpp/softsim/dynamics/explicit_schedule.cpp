#include "softsim/dynamics/explicit_solver.hpp"

#include <algorithm>

namespace softsim::dynamics {

// Parts (one per thread) are runs of tiles of about equal cost. A node whose elements all belong
// to one part is updated by that part right after its ready tile; the others (along the part
// boundaries) after the mid-step barrier, shared equally among the parts. Per-node lists of the
// scene's special entries let whoever updates a node do everything it needs.
void ExplicitSolver::build_schedule() {
  const int T = opt_.threads;
  const int tiles = elements_.num_tiles();
  std::vector<double> cum(tiles + 1, 0.0);
  for (int t = 0; t < tiles; ++t) cum[t + 1] = cum[t] + elements_.tile_cost(t);
  tile_begin_.assign(T + 1, tiles);
  tile_begin_[0] = 0;
  int t = 0;
  for (int p = 1; p < T; ++p) {
    const double target = cum[tiles] * p / T;
    while (t < tiles && cum[t + 1] <= target) ++t;
    tile_begin_[p] = t;
  }
  pressure_nodes_.assign(T + 1, 0);
  for (int p = 0; p <= T; ++p) pressure_nodes_[p] = static_cast<int>(static_cast<long>(n_) * p / T);
  // Special nodes: those with constraints, loads, a trajectory or the probe (rigid tools act in
  // a pass of their own after the update, explicit_contact.cpp).
  std::vector<char> special_node(n_, 0);
  for (const auto& d : dofs_) special_node[d.node] = 1;
  for (const auto& l : loads_) special_node[l.node] = 1;
  for (int node : opt_.trajectory_nodes) special_node[node] = 1;
  if (scene_.has_probe) special_node[scene_.probe.node] = 1;
  // Each list holds the plain nodes first, then the special ones (from `split` on). Deferred
  // nodes can be updated by any thread once every element is done: they are pooled (in tile
  // order) and each part gets an equal share, so that no thread idles at the end of the step.
  local_begin_.assign(tiles + 1, 0);
  local_split_.assign(tiles, 0);
  local_nodes_.clear();
  std::vector<int> deferred_plain, deferred_special;
  for (int p = 0; p < T; ++p)
    for (int q = tile_begin_[p]; q < tile_begin_[p + 1]; ++q) {
      std::vector<int> plain, special;
      for (const int* it = elements_.ready_nodes_begin(q); it != elements_.ready_nodes_end(q); ++it) {
        const bool local = elements_.first_tile(*it) >= tile_begin_[p];
        const bool is_special = special_node[*it];
        (local ? (is_special ? special : plain) : (is_special ? deferred_special : deferred_plain)).push_back(*it);
      }
      local_nodes_.insert(local_nodes_.end(), plain.begin(), plain.end());
      local_split_[q] = static_cast<int>(local_nodes_.size());
      local_nodes_.insert(local_nodes_.end(), special.begin(), special.end());
      local_begin_[q + 1] = static_cast<int>(local_nodes_.size());
    }
  deferred_begin_.assign(T + 1, 0);
  deferred_split_.assign(T, 0);
  deferred_nodes_.clear();
  for (int p = 0; p < T; ++p) {
    const auto share = [&](const std::vector<int>& v, int q) { return v.begin() + static_cast<long>(v.size()) * q / T; };
    deferred_nodes_.insert(deferred_nodes_.end(), share(deferred_plain, p), share(deferred_plain, p + 1));
    deferred_split_[p] = static_cast<int>(deferred_nodes_.size());
    deferred_nodes_.insert(deferred_nodes_.end(), share(deferred_special, p), share(deferred_special, p + 1));
    deferred_begin_[p + 1] = static_cast<int>(deferred_nodes_.size());
  }
  // Per-node lists of special entries (sorted by node already for dofs and loads).
  auto csr = [&](std::vector<int>& begin, auto node_of, int count) {
    begin.assign(n_ + 1, 0);
    for (int e = 0; e < count; ++e) ++begin[node_of(e) + 1];
    for (int i = 0; i < n_; ++i) begin[i + 1] += begin[i];
  };
  csr(dof_begin_, [&](int e) { return dofs_[e].node; }, static_cast<int>(dofs_.size()));
  csr(load_begin_, [&](int e) { return loads_[e].node; }, static_cast<int>(loads_.size()));
  trajectory_order_.resize(opt_.trajectory_nodes.size());
  for (std::size_t j = 0; j < trajectory_order_.size(); ++j) trajectory_order_[j] = static_cast<int>(j);
  std::stable_sort(trajectory_order_.begin(), trajectory_order_.end(),
                   [&](int a, int b) { return opt_.trajectory_nodes[a] < opt_.trajectory_nodes[b]; });
  csr(trajectory_begin_, [&](int j) { return opt_.trajectory_nodes[trajectory_order_[j]]; },
      static_cast<int>(trajectory_order_.size()));
}

// A node is held when constraints fix all three of its components and none of them moves: its
// update is the constraint's value alone (a fixed constraint's reaction comes from reactions(),
// not from the step), so the step neither gathers nor integrates it.
void ExplicitSolver::mark_held_nodes() {
  held_.assign(n_, 0);
  if (!opt_.skip_held_nodes) return;
  for (int i = 0; i < n_; ++i) {
    int components = 0;
    bool moves = false;
    for (int e = dof_begin_[i]; e < dof_begin_[i + 1]; ++e) {
      components |= 1 << dofs_[e].component;
      moves = moves || moving_[dofs_[e].constraint];
    }
    held_[i] = components == 7 && !moves;
  }
}

}  // namespace softsim::dynamics
