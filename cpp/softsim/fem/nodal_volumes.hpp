#pragma once
// The node ↔ element weights of the average-nodal-pressure element (nodal_pressure.hpp) and the
// nodal volume ratio J_a = Σ_{e∋a} w_ae J_e built on them. The static assembly and the explicit
// engine both sum here, in the stored order, so their J_a agree bit for bit for equal element
// ratios.
#include <vector>

#include "softsim/fem/element_kind.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::fem {

// Node → incident ANP elements, with J_a = Σ weight · J_e.
struct NodalVolumes {
  std::vector<int> begin;      // n + 1 offsets into element / weight
  std::vector<int> element;    // incident ANP elements of each node, ascending
  std::vector<double> weight;  // ⁰V_e / (4 V_a)
  std::vector<double> volume;  // V_a (0 for a node without ANP elements)

  bool has_elements(int node) const { return begin[node] != begin[node + 1]; }
};

NodalVolumes nodal_volumes(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds,
                           const std::vector<double>& element_volume);

// J_a of a node with ANP elements, from the element volume ratios J_e indexed as nv.element.
inline double nodal_volume_ratio(const NodalVolumes& nv, int node, const double* element_ratio) {
  double J = 0;
  for (int p = nv.begin[node]; p < nv.begin[node + 1]; ++p) J += nv.weight[p] * element_ratio[nv.element[p]];
  return J;
}

}  // namespace softsim::fem
