#pragma once
// VTK XML UnstructuredGrid (.vtu, ASCII) export so any mesh or result opens in ParaView.
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::io {

struct VtuFields {
  std::map<std::string, std::vector<Eigen::Vector3d>> point_vectors;  // e.g. displacement, velocity
  std::map<std::string, std::vector<double>> point_scalars;
  std::map<std::string, std::vector<int>> cell_ints;  // e.g. element kind, region
};

// Positions written are the reference nodes (apply the "displacement" vector with
// ParaView's Warp By Vector). Written atomically.
void write_vtu(const std::string& path, const mesh::TetMesh& mesh, const VtuFields& fields);

}  // namespace softsim::io
