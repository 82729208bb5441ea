#include "softsim/regions/primary_region.hpp"

#include <cmath>
#include <string>

#include "softsim/io/errors.hpp"

namespace softsim::regions {

PrimaryRegion select_primary_region(const mesh::TetMesh& mesh, int centre, double radius,
                                    const std::vector<char>* removed) {
  if (centre < 0 || centre >= mesh.num_nodes())
    throw InputError("regions: contact node " + std::to_string(centre) + " out of range");
  if (!(radius > 0) || !std::isfinite(radius)) throw InputError("regions: the primary radius must be positive");
  PrimaryRegion r;
  r.centre = centre;
  r.radius = radius;
  const Eigen::Vector3d c = mesh.nodes[centre];
  std::vector<char> near(mesh.num_nodes(), 0);
  for (int i = 0; i < mesh.num_nodes(); ++i) near[i] = (mesh.nodes[i] - c).norm() <= radius;
  // The centre's neighbours count as near whatever the radius, so that every node sharing an
  // element with the centre is interior: a contact triangle on the centre is then always
  // solved every frame.
  for (int e = 0; e < mesh.num_tets(); ++e) {
    if (removed && (*removed)[e]) continue;
    const auto& t = mesh.tets[e];
    if (t[0] == centre || t[1] == centre || t[2] == centre || t[3] == centre)
      for (int n : t) near[n] = 1;
  }
  // 1: touched by a primary element; 2: by a secondary one (both: interface).
  std::vector<char> touched(mesh.num_nodes(), 0);
  for (int e = 0; e < mesh.num_tets(); ++e) {
    if (removed && (*removed)[e]) {
      ++r.removed_elements;
      continue;
    }
    const auto& t = mesh.tets[e];
    const bool primary = near[t[0]] || near[t[1]] || near[t[2]] || near[t[3]];
    if (primary) r.elements.push_back(e);
    for (int n : t) touched[n] |= primary ? 1 : 2;
  }
  r.local.assign(mesh.num_nodes(), -1);
  r.interior.assign(mesh.num_nodes(), 0);
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    if (!(touched[i] & 1)) continue;
    r.local[i] = static_cast<int>(r.nodes.size());
    r.nodes.push_back(i);
    if (touched[i] & 2) {
      r.interface.push_back(i);
      r.interface_local.push_back(r.local[i]);
    } else {
      r.interior[i] = 1;
    }
  }
  r.submesh.nodes.reserve(r.nodes.size());
  for (int i : r.nodes) r.submesh.nodes.push_back(mesh.nodes[i]);
  r.submesh.tets.reserve(r.elements.size());
  for (int e : r.elements) {
    mesh::Tet t = mesh.tets[e];
    for (int& n : t) n = r.local[n];
    r.submesh.tets.push_back(t);
  }
  return r;
}

}  // namespace softsim::regions
