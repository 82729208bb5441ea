#pragma once
// Legacy VTK ASCII UNSTRUCTURED_GRID reader (classic "CELLS n size" layout and the 5.1
// OFFSETS/CONNECTIVITY layout). Keeps VTK_TETRA cells; integer one-component cell arrays,
// SCALARS or arrays of a FIELD block (how VTK 9 writes every array without an attribute role),
// become element tags of the same name (e.g. "materials" of the breast mesh); other arrays,
// point data and METADATA blocks are read and dropped.
#include <string>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::mesh {

TetMesh read_vtk_legacy(const std::string& text, const std::string& source);

}  // namespace softsim::mesh
