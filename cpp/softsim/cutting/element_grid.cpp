#include "softsim/cutting/element_grid.hpp"

#include <algorithm>
#include <cmath>

namespace softsim::cutting {

namespace {

std::pair<Eigen::Vector3d, Eigen::Vector3d> element_box(const mesh::TetMesh& mesh, int e) {
  Eigen::Vector3d lo = mesh.nodes[mesh.tets[e][0]], hi = lo;
  for (int a = 1; a < 4; ++a) {
    lo = lo.cwiseMin(mesh.nodes[mesh.tets[e][a]]);
    hi = hi.cwiseMax(mesh.nodes[mesh.tets[e][a]]);
  }
  return {lo, hi};
}

}  // namespace

ElementGrid::ElementGrid(const mesh::TetMesh& mesh) : seen_(mesh.num_tets(), 0) {
  const auto [lo, hi] = mesh::bounding_box(mesh);
  const Eigen::Vector3d extent = (hi - lo).cwiseMax(1e-300);
  // Cells about the size of an element: (box volume / elements)^(1/3) per side, at most one
  // cell per element along the whole grid so a thin or sparse mesh cannot ask for many cells.
  const double box_volume = extent.prod();
  const double side = std::cbrt(box_volume / std::max(1, mesh.num_tets()));
  long cells = 1;
  for (int k = 0; k < 3; ++k) {
    dims_[k] = std::clamp(static_cast<int>(std::ceil(extent[k] / side)), 1, std::max(1, mesh.num_tets()));
    cells *= dims_[k];
  }
  while (cells > 2L * std::max(1, mesh.num_tets())) {  // round-off at the clamp: halve the finest axis
    int k = static_cast<int>(std::max_element(dims_, dims_ + 3) - dims_);
    cells = cells / dims_[k] * ((dims_[k] + 1) / 2);
    dims_[k] = (dims_[k] + 1) / 2;
  }
  origin_ = lo;
  for (int k = 0; k < 3; ++k) cell_size_[k] = extent[k] / dims_[k];

  auto cell_range = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, int first[3], int last[3]) {
    for (int k = 0; k < 3; ++k) {
      first[k] = std::clamp(static_cast<int>(std::floor((a[k] - origin_[k]) / cell_size_[k])), 0, dims_[k] - 1);
      last[k] = std::clamp(static_cast<int>(std::floor((b[k] - origin_[k]) / cell_size_[k])), 0, dims_[k] - 1);
    }
  };
  // Two passes: count, then fill (CSR).
  cell_begin_.assign(num_cells() + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> fill;
    if (pass == 1) {
      for (int c = 0; c < num_cells(); ++c) cell_begin_[c + 1] += cell_begin_[c];
      cell_elements_.resize(cell_begin_.back());
      fill.assign(cell_begin_.begin(), cell_begin_.end() - 1);
    }
    for (int e = 0; e < mesh.num_tets(); ++e) {
      const auto [elo, ehi] = element_box(mesh, e);
      int first[3], last[3];
      cell_range(elo, ehi, first, last);
      for (int z = first[2]; z <= last[2]; ++z)
        for (int y = first[1]; y <= last[1]; ++y)
          for (int x = first[0]; x <= last[0]; ++x) {
            const int c = x + dims_[0] * (y + dims_[1] * z);
            if (pass == 0)
              ++cell_begin_[c + 1];
            else
              cell_elements_[fill[c]++] = e;
          }
    }
  }
}

void ElementGrid::candidates(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::vector<int>& out) const {
  out.clear();
  if (++query_ == 0) {  // the stamp wrapped: forget every earlier query
    std::fill(seen_.begin(), seen_.end(), 0u);
    query_ = 1;
  }
  int first[3], last[3];
  for (int k = 0; k < 3; ++k) {
    const double a = (lo[k] - origin_[k]) / cell_size_[k], b = (hi[k] - origin_[k]) / cell_size_[k];
    if (!(b >= 0) || !(a < dims_[k])) return;  // wholly outside the mesh's box (or not finite)
    first[k] = std::max(0, static_cast<int>(std::floor(a)));
    last[k] = std::min(dims_[k] - 1, static_cast<int>(std::floor(b)));
  }
  for (int z = first[2]; z <= last[2]; ++z)
    for (int y = first[1]; y <= last[1]; ++y)
      for (int x = first[0]; x <= last[0]; ++x) {
        const int c = x + dims_[0] * (y + dims_[1] * z);
        for (int p = cell_begin_[c]; p < cell_begin_[c + 1]; ++p) {
          const int e = cell_elements_[p];
          if (seen_[e] == query_) continue;
          seen_[e] = query_;
          out.push_back(e);
        }
      }
  std::sort(out.begin(), out.end());
}

double largest_displacement(const double* u, int num_nodes) {
  if (!u) return 0.0;
  double largest2 = 0;
  for (int a = 0; a < num_nodes; ++a)
    largest2 = std::max(largest2, u[3 * a] * u[3 * a] + u[3 * a + 1] * u[3 * a + 1] + u[3 * a + 2] * u[3 * a + 2]);
  return std::sqrt(largest2);
}

}  // namespace softsim::cutting
