#pragma once
// What the two VTK readers (legacy .vtk and XML .vtu) share once they have the arrays: keep the
// VTK_TETRA cells, check their point indices, carry integer cell arrays along as element tags,
// and drop the points no tetrahedron uses.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::mesh {

inline constexpr int kVtkTetra = 10;

// Cells in VTK's flat layout: cell c has the points connectivity[offsets[c] .. offsets[c + 1]).
struct VtkCells {
  std::vector<std::int64_t> offsets = {0};
  std::vector<std::int64_t> connectivity;
  std::vector<int> types;
  std::size_t size() const { return offsets.size() - 1; }
};

// `cell_tags`: integer cell arrays (one value per cell), kept for the tetrahedra. Without a
// "region" array, the tag "region" is a copy of "materials" (the breast mesh's name for it) or
// "gmsh:physical" (meshio's, for a converted Gmsh mesh), else 0. InputError naming
// `source` for a tetrahedron without 4 points, a point index out of range, or no tetrahedron.
TetMesh tets_from_vtk_cells(std::vector<Eigen::Vector3d> points, const VtkCells& cells,
                            const std::map<std::string, std::vector<int>>& cell_tags, const std::string& source);

}  // namespace softsim::mesh
