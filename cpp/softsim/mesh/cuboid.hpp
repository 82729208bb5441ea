#pragma once
// The structured cuboid of 000 §2.2.1 (Figs. 2–3): nx × ny × nz hexahedral cells, each split
// into 5 tetrahedra; the two splits alternate with the parity of (i + j + k) so that the face
// diagonals of neighbouring cells coincide and the mesh is conforming.
#include <array>

#include <Eigen/Core>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::mesh {

struct CuboidSpec {
  std::array<int, 3> cells = {1, 1, 1};          // cubes along x, y, z
  Eigen::Vector3d size = Eigen::Vector3d::Ones();  // edge lengths of the whole box (m)
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
};

// Node (i, j, k) has index i + (nx+1)(j + (ny+1) k). Node sets: bottom (z min), top (z max),
// x_min, x_max, y_min, y_max, sides (union of the four lateral faces), boundary.
// Element tags: "layer" = k of the cell (0 at the bottom), "region" = 0.
TetMesh make_cuboid(const CuboidSpec& spec);

}  // namespace softsim::mesh
