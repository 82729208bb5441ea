#include "softsim/mesh/tet_mesh.hpp"

#include <algorithm>
#include <cmath>

#include "softsim/io/errors.hpp"

namespace softsim::mesh {

double signed_volume(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                     const Eigen::Vector3d& x2, const Eigen::Vector3d& x3) {
  return (x1 - x0).dot((x2 - x0).cross(x3 - x0)) / 6.0;
}

double signed_volume(const TetMesh& mesh, const Tet& t) {
  return signed_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]);
}

void orient_positively(TetMesh& mesh, const std::string& source) {
  // A volume below 1e-14 of the bounding-box volume is taken as degenerate.
  const auto [lo, hi] = bounding_box(mesh);
  const Eigen::Vector3d ext = hi - lo;
  const double tol = 1e-14 * std::max(ext.prod(), 1e-300);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    Tet& t = mesh.tets[e];
    const double v = signed_volume(mesh, t);
    if (!std::isfinite(v) || std::fabs(v) <= tol)
      throw InputError(source + ": element " + std::to_string(e) +
                       ": expected a tetrahedron with non-zero volume, got volume " +
                       std::to_string(v));
    if (v < 0) std::swap(t[1], t[2]);
  }
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> bounding_box(const TetMesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
  for (const auto& x : mesh.nodes) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  if (mesh.nodes.empty()) lo = hi = Eigen::Vector3d::Zero();
  return {lo, hi};
}

void scale(TetMesh& mesh, double factor) {
  for (auto& x : mesh.nodes) x *= factor;
}

std::vector<char> nodes_in_tets(const TetMesh& mesh) {
  std::vector<char> used(mesh.nodes.size(), 0);
  for (const auto& t : mesh.tets)
    for (int v : t) used[v] = 1;
  return used;
}

void drop_unused_nodes(TetMesh& mesh) {
  const std::vector<char> used = nodes_in_tets(mesh);
  std::vector<int> new_index(mesh.nodes.size(), -1);
  std::vector<Eigen::Vector3d> kept;
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
    if (used[i]) {
      new_index[i] = static_cast<int>(kept.size());
      kept.push_back(mesh.nodes[i]);
    }
  if (kept.size() == mesh.nodes.size()) return;
  mesh.nodes = std::move(kept);
  for (auto& t : mesh.tets)
    for (int& v : t) v = new_index[v];
  for (auto& tri : mesh.boundary)
    for (int& v : tri) v = new_index[v];
  for (auto& [name, set] : mesh.node_sets) {
    std::vector<int> renamed;
    for (int v : set)
      if (new_index[v] >= 0) renamed.push_back(new_index[v]);
    set = std::move(renamed);
  }
}

}  // namespace softsim::mesh
