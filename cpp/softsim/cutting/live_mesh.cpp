#include "softsim/cutting/live_mesh.hpp"

namespace softsim::cutting {

LiveMesh live_mesh(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds,
                   const std::function<bool(int)>& removed) {
  LiveMesh live;
  live.mesh.nodes = mesh.nodes;
  live.mesh.node_sets = mesh.node_sets;
  for (int e = 0; e < mesh.num_tets(); ++e)
    if (!removed(e)) {
      live.mesh.tets.push_back(mesh.tets[e]);
      live.kinds.push_back(kinds[e]);
    }
  return live;
}

}  // namespace softsim::cutting
