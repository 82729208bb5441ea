#pragma once
// Wavefront OBJ surfaces: "v x y z" vertices and "f i j k ..." faces (1-based or negative
// relative indices, "i/t/n" forms; faces of more than 3 vertices are fanned into triangles).
// Everything else (normals, texture coordinates, groups, materials) is skipped.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::mesh {

struct TriangleSurface {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Triangle> triangles;  // 0-based vertex indices
};

// InputError naming `source` and the line for a malformed vertex or face, and for a file
// without faces.
TriangleSurface read_obj(const std::string& text, const std::string& source);

}  // namespace softsim::mesh
