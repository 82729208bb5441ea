#include "softsim/fem/nodal_volumes.hpp"

namespace softsim::fem {

NodalVolumes nodal_volumes(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds,
                           const std::vector<double>& element_volume) {
  const int n = mesh.num_nodes();
  NodalVolumes nv;
  nv.begin.assign(n + 1, 0);
  nv.volume.assign(n, 0.0);
  for (int e = 0; e < mesh.num_tets(); ++e)
    if (volumetric_at_nodes(kinds[e]))
      for (int a : mesh.tets[e]) {
        ++nv.begin[a + 1];
        nv.volume[a] += 0.25 * element_volume[e];
      }
  for (int a = 0; a < n; ++a) nv.begin[a + 1] += nv.begin[a];
  nv.element.resize(nv.begin[n]);
  nv.weight.resize(nv.begin[n]);
  std::vector<int> fill(nv.begin.begin(), nv.begin.end() - 1);
  for (int e = 0; e < mesh.num_tets(); ++e)
    if (volumetric_at_nodes(kinds[e]))
      for (int a : mesh.tets[e]) {
        nv.element[fill[a]] = e;
        nv.weight[fill[a]++] = 0.25 * element_volume[e] / nv.volume[a];
      }
  return nv;
}

}  // namespace softsim::fem
