#include "softsim/dynamics/contact_search.hpp"

#include <algorithm>
#include <cmath>

namespace softsim::dynamics {

namespace {

// A quarter of the tool's size: wide enough that a tool pressed a few millimetres rarely
// triggers a new list, narrow enough that the list stays near the tool.
double default_margin(const RigidTool& tool, const std::vector<Eigen::Vector3d>& reference) {
  switch (tool.shape) {
    case RigidTool::Shape::sphere:
      return 0.25 * tool.radius;
    case RigidTool::Shape::capsule:
      return 0.25 * (tool.radius + tool.half_axis.norm());
    case RigidTool::Shape::mesh:
      return 0.125 * (tool.surface->upper() - tool.surface->lower()).norm();
    case RigidTool::Shape::plane:
      break;
  }
  // A plane: a twentieth of the nodes' extent.
  Eigen::Vector3d lo = reference.empty() ? Eigen::Vector3d::Zero() : reference[0], hi = lo;
  for (const auto& x : reference) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return std::max(0.05 * (hi - lo).norm(), 1e-9);
}

}  // namespace

void ContactSearch::setup(const std::vector<RigidTool>& tools, std::vector<std::vector<int>> entries,
                          const std::vector<int>& entry_node, const std::vector<Eigen::Vector3d>& entry_position,
                          bool enabled) {
  enabled_ = enabled;
  tools_.assign(tools.size(), ToolGrid{});
  for (std::size_t k = 0; k < tools.size(); ++k) {
    ToolGrid& g = tools_[k];
    g.entries = std::move(entries[k]);
    for (int e : g.entries) {
      g.nodes.push_back(entry_node[e]);
      g.reference.push_back(entry_position[e]);
    }
    g.margin = tools[k].search_margin > 0 ? tools[k].search_margin : default_margin(tools[k], g.reference);
    g.x0.assign(3 * g.entries.size(), 0.0);
    g.mark.assign(g.entries.size(), 0);
    g.list.reserve(g.entries.size());
    g.scratch.reserve(g.entries.size());
    g.cell_items.reserve(g.entries.size());
  }
}

void ContactSearch::reset() {
  for (ToolGrid& g : tools_) {
    g.built = g.listed = false;
    g.list.clear();
    g.rebuilds = g.queries = 0;
  }
}

void ContactSearch::build_grid(ToolGrid& g, const double* u) {
  const int n = static_cast<int>(g.entries.size());
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (int j = 0; j < n; ++j)
    for (int c = 0; c < 3; ++c) {
      const double x = g.reference[j][c] + u[3 * g.nodes[j] + c];
      g.x0[3 * j + c] = x;
      lo[c] = std::min(lo[c], x);
      hi[c] = std::max(hi[c], x);
    }
  if (n == 0) lo = hi = Eigen::Vector3d::Zero();
  // Cells of the margin's size, coarser if that would make more than 8 cells per node.
  g.cell = g.margin;
  const double limit = 8.0 * n + 8.0;
  for (;;) {
    double cells = 1;
    for (int c = 0; c < 3; ++c) cells *= std::floor((hi[c] - lo[c]) / g.cell) + 1;
    if (cells <= limit) break;
    g.cell *= 1.5;
  }
  g.origin = lo;
  for (int c = 0; c < 3; ++c) g.dims[c] = static_cast<int>(std::floor((hi[c] - lo[c]) / g.cell)) + 1;
  const int cells = g.dims[0] * g.dims[1] * g.dims[2];
  g.cell_begin.assign(cells + 1, 0);
  auto cell_of = [&](int j) {
    int idx[3];
    for (int c = 0; c < 3; ++c)
      idx[c] = std::min(g.dims[c] - 1, static_cast<int>(std::floor((g.x0[3 * j + c] - g.origin[c]) / g.cell)));
    return (idx[2] * g.dims[1] + idx[1]) * g.dims[0] + idx[0];
  };
  for (int j = 0; j < n; ++j) ++g.cell_begin[cell_of(j) + 1];
  for (int q = 0; q < cells; ++q) g.cell_begin[q + 1] += g.cell_begin[q];
  g.cell_items.assign(n, 0);
  g.scratch.assign(g.cell_begin.begin(), g.cell_begin.end() - 1);
  for (int j = 0; j < n; ++j) g.cell_items[g.scratch[cell_of(j)]++] = j;
  g.built = true;
  ++g.rebuilds;
}

void ContactSearch::make_list(ToolGrid& g, const RigidTool& tool, const Eigen::Vector3d& centre, const double* force) {
  const double m = g.margin;
  g.scratch.clear();
  Eigen::Vector3d lo, hi;
  if (tool.bounds(centre, lo, hi)) {
    g.allowed_lo = lo.array() - 0.5 * m;
    g.allowed_hi = hi.array() + 0.5 * m;
    const Eigen::Vector3d slo = lo.array() - m, shi = hi.array() + m;
    int a[3], b[3];
    bool empty = false;
    for (int c = 0; c < 3; ++c) {
      const double from = std::floor((slo[c] - g.origin[c]) / g.cell), to = std::floor((shi[c] - g.origin[c]) / g.cell);
      a[c] = static_cast<int>(std::max(from, 0.0));
      b[c] = static_cast<int>(std::min(to, static_cast<double>(g.dims[c] - 1)));
      empty = empty || to < 0 || from > g.dims[c] - 1;
    }
    if (!empty)
      for (int z = a[2]; z <= b[2]; ++z)
        for (int y = a[1]; y <= b[1]; ++y)
          for (int x = a[0]; x <= b[0]; ++x) {
            const int q = (z * g.dims[1] + y) * g.dims[0] + x;
            for (int p = g.cell_begin[q]; p < g.cell_begin[q + 1]; ++p) {
              const int j = g.cell_items[p];
              const double* x0 = &g.x0[3 * j];
              if (x0[0] >= slo[0] && x0[0] <= shi[0] && x0[1] >= slo[1] && x0[1] <= shi[1] && x0[2] >= slo[2] &&
                  x0[2] <= shi[2])
                g.scratch.push_back(j);
            }
          }
  } else {  // a plane: (x − c)·n < 0 inside
    const double slack = m * tool.normal.cwiseAbs().sum();
    const double offset = tool.normal.dot(centre);
    g.allowed_offset = offset + 0.5 * slack;
    for (int j = 0; j < static_cast<int>(g.entries.size()); ++j)
      if (tool.normal.dot(Eigen::Vector3d(g.x0[3 * j], g.x0[3 * j + 1], g.x0[3 * j + 2])) - offset <= slack)
        g.scratch.push_back(j);
  }
  for (int j : g.scratch) g.mark[j] = 1;
  // Entries in contact at the last step stay listed once more.
  const auto local_of = [&](int e) {
    return static_cast<int>(std::lower_bound(g.entries.begin(), g.entries.end(), e) - g.entries.begin());
  };
  for (int e : g.list)
    if (force[3 * e] != 0 || force[3 * e + 1] != 0 || force[3 * e + 2] != 0) {
      const int j = local_of(e);
      if (!g.mark[j]) {
        g.mark[j] = 1;
        g.scratch.push_back(j);
      }
    }
  std::sort(g.scratch.begin(), g.scratch.end());
  g.list.clear();
  for (int j : g.scratch) {
    g.list.push_back(g.entries[j]);
    g.mark[j] = 0;
  }
  g.listed = true;
  ++g.queries;
}

const std::vector<int>& ContactSearch::candidates(int k, const RigidTool& tool, const Eigen::Vector3d& centre,
                                                  const double* u, const double* force) {
  ToolGrid& g = tools_[k];
  if (!enabled_) return g.entries;
  const double half = 0.5 * g.margin;
  bool moved = !g.built;
  const int n = static_cast<int>(g.entries.size());
  for (int j = 0; j < n && !moved; ++j) {
    const double* x0 = &g.x0[3 * j];
    const double* ui = u + 3 * g.nodes[j];
    const Eigen::Vector3d& X = g.reference[j];
    moved = std::abs(X[0] + ui[0] - x0[0]) > half || std::abs(X[1] + ui[1] - x0[1]) > half ||
            std::abs(X[2] + ui[2] - x0[2]) > half;
  }
  if (moved) build_grid(g, u);
  bool relist = moved || !g.listed;
  if (!relist) {
    Eigen::Vector3d lo, hi;
    if (tool.bounds(centre, lo, hi))
      relist = (lo.array() < g.allowed_lo.array()).any() || (hi.array() > g.allowed_hi.array()).any();
    else
      relist = tool.normal.dot(centre) > g.allowed_offset;
  }
  if (relist) make_list(g, tool, centre, force);
  return g.list;
}

}  // namespace softsim::dynamics
