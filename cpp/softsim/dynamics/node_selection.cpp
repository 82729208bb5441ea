#include "softsim/dynamics/node_selection.hpp"

namespace softsim::dynamics {

int nearest_node(const mesh::TetMesh& mesh, const Eigen::Vector3d& point) {
  int best = -1;
  double best_d = 0;
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    const double d = (mesh.nodes[i] - point).squaredNorm();
    if (best < 0 || d < best_d) {
      best = i;
      best_d = d;
    }
  }
  return best;
}

std::vector<int> nodes_in_sphere(const mesh::TetMesh& mesh, const Eigen::Vector3d& center, double radius) {
  std::vector<int> out;
  for (int i = 0; i < mesh.num_nodes(); ++i)
    if ((mesh.nodes[i] - center).norm() <= radius) out.push_back(i);
  return out;
}

std::vector<int> nodes_in_box(const mesh::TetMesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const auto [bmin, bmax] = mesh::bounding_box(mesh);
  const double tol = 1e-9 * (bmax - bmin).norm();
  std::vector<int> out;
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    const Eigen::Vector3d& x = mesh.nodes[i];
    if ((x.array() >= lo.array() - tol).all() && (x.array() <= hi.array() + tol).all()) out.push_back(i);
  }
  return out;
}

}  // namespace softsim::dynamics
