#include "softsim/mesh/quality.hpp"

#include <algorithm>
#include <cmath>

namespace softsim::mesh {

TetQuality tet_quality(const TetMesh& mesh, int element) {
  const Tet& t = mesh.tets[element];
  const Eigen::Vector3d* x[4] = {&mesh.nodes[t[0]], &mesh.nodes[t[1]], &mesh.nodes[t[2]],
                                 &mesh.nodes[t[3]]};
  TetQuality q;
  q.volume = signed_volume(*x[0], *x[1], *x[2], *x[3]);
  // Face i is opposite vertex i; its (unnormalised) outward normal.
  Eigen::Vector3d normal[4];
  double max_area = 0;
  for (int i = 0; i < 4; ++i) {
    const int a = (i + 1) % 4, b = (i + 2) % 4, c = (i + 3) % 4;
    Eigen::Vector3d n = (*x[b] - *x[a]).cross(*x[c] - *x[a]);
    if (n.dot(*x[i] - *x[a]) > 0) n = -n;
    normal[i] = n;
    max_area = std::max(max_area, 0.5 * n.norm());
  }
  q.min_altitude = max_area > 0 ? 3.0 * q.volume / max_area : 0.0;
  q.min_dihedral_deg = 180.0;
  q.max_dihedral_deg = 0.0;
  // The dihedral angle at the edge shared by faces i and j is pi minus the angle between
  // their outward normals.
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const double c = -normal[i].dot(normal[j]) / (normal[i].norm() * normal[j].norm());
      const double angle = std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI;
      q.min_dihedral_deg = std::min(q.min_dihedral_deg, angle);
      q.max_dihedral_deg = std::max(q.max_dihedral_deg, angle);
    }
  q.min_edge = 1e300;
  q.max_edge = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const double l = (*x[i] - *x[j]).norm();
      q.min_edge = std::min(q.min_edge, l);
      q.max_edge = std::max(q.max_edge, l);
    }
  return q;
}

QualityReport quality_report(const TetMesh& mesh, double sliver_threshold_deg) {
  QualityReport r;
  r.nodes = mesh.num_nodes();
  r.tets = mesh.num_tets();
  r.boundary_triangles = static_cast<int>(mesh.boundary.size());
  r.sliver_threshold_deg = sliver_threshold_deg;
  r.min_volume = r.min_dihedral_deg = r.min_altitude = r.min_edge = 1e300;
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const TetQuality q = tet_quality(mesh, e);
    r.total_volume += q.volume;
    r.min_volume = std::min(r.min_volume, q.volume);
    r.max_volume = std::max(r.max_volume, q.volume);
    r.min_dihedral_deg = std::min(r.min_dihedral_deg, q.min_dihedral_deg);
    r.max_dihedral_deg = std::max(r.max_dihedral_deg, q.max_dihedral_deg);
    r.min_altitude = std::min(r.min_altitude, q.min_altitude);
    r.min_edge = std::min(r.min_edge, q.min_edge);
    r.max_edge = std::max(r.max_edge, q.max_edge);
    if (q.min_dihedral_deg < sliver_threshold_deg) r.slivers.push_back(e);
  }
  if (mesh.tets.empty()) r.min_volume = r.min_dihedral_deg = r.min_altitude = r.min_edge = 0;
  return r;
}

}  // namespace softsim::mesh
