#pragma once
// Gmsh .msh reader: format 1.0 ($NOD/$ELM, ASCII), 2.2 and 4.1, ASCII or binary (file type 1,
// in this machine's byte order). Keeps the 4-node tetrahedra; their physical group becomes the
// element tags "physical" and "region". Node ids may have gaps.
#include <string>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::mesh {

// `text`: the whole file (binary files included). `source` names the file in error messages.
// Coordinates are returned as stored (no scaling).
TetMesh read_gmsh(const std::string& text, const std::string& source);

}  // namespace softsim::mesh
