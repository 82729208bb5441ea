#pragma once
// Boundary surface of a tetrahedral mesh and its topological checks.
#include <string>
#include <vector>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::mesh {

// Faces used by exactly one tet, oriented outward. A face shared by more than two tets means
// a non-manifold mesh: InputError naming `source` and the face.
std::vector<Triangle> extract_boundary(const TetMesh& mesh, const std::string& source);

// Sorted unique nodes of mesh.boundary.
std::vector<int> boundary_nodes(const TetMesh& mesh);

struct FaceCensus {
  int interior_faces = 0;   // shared by exactly two tets
  int boundary_faces = 0;   // used by exactly one tet
  int overshared_faces = 0; // used by three or more (a defect)
  int surface_vertices = 0;
  int surface_edges = 0;
  int euler_characteristic = 0;  // V - E + F of the boundary surface (2 for a closed sphere-like surface)
  int non_manifold_edges = 0;    // surface edges not shared by exactly two boundary triangles
  int inward_triangles = 0;      // boundary triangles whose normal points into their tet
};
FaceCensus census(const TetMesh& mesh);

}  // namespace softsim::mesh
