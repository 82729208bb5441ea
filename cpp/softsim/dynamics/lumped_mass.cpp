#include "softsim/dynamics/lumped_mass.hpp"

namespace softsim::dynamics {

std::vector<double> lumped_mass(const mesh::TetMesh& mesh, double density) {
  std::vector<double> m(mesh.num_nodes(), 0.0);
  for (const auto& t : mesh.tets) {
    const double quarter = 0.25 * density * mesh::signed_volume(mesh, t);  // 000 Fig. 7
    for (int a = 0; a < 4; ++a) m[t[a]] += quarter;
  }
  return m;
}

}  // namespace softsim::dynamics
