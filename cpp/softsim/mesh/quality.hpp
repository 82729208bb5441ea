#pragma once
// Element quality: what limits the explicit step (minimum altitude) and what spoils accuracy
// (slivers with tiny dihedral angles).
#include <vector>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::mesh {

struct TetQuality {
  double volume = 0;
  double min_dihedral_deg = 0;
  double max_dihedral_deg = 0;
  double min_altitude = 0;  // 3V / (largest face area): the stability length of 000 eq. 34
  double min_edge = 0;
  double max_edge = 0;
};
TetQuality tet_quality(const TetMesh& mesh, int element);

struct QualityReport {
  int nodes = 0;
  int tets = 0;
  int boundary_triangles = 0;
  double total_volume = 0;
  double min_volume = 0;
  double max_volume = 0;
  double min_dihedral_deg = 0;
  double max_dihedral_deg = 0;
  double min_altitude = 0;
  double min_edge = 0;
  double max_edge = 0;
  double sliver_threshold_deg = 0;
  std::vector<int> slivers;  // elements whose smallest dihedral angle is below the threshold
};
QualityReport quality_report(const TetMesh& mesh, double sliver_threshold_deg = 5.0);

}  // namespace softsim::mesh
