#pragma once
// Gmsh ASCII .msh reader: format 1.0 ($NOD/$ELM), 2.2 and 4.1. Keeps the 4-node tetrahedra;
// their physical group becomes the element tag "physical". Node ids may have gaps.
#include <string>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::mesh {

// `source` names the file in error messages. Coordinates are returned as stored (no scaling).
TetMesh read_gmsh(const std::string& text, const std::string& source);

}  // namespace softsim::mesh
