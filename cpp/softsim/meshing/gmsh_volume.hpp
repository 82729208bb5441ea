#pragma once
// Closed triangle surfaces (.obj, .stl) made into tetrahedral volumes through the Gmsh C++ API
// (Debian libgmsh-dev). The surface is reclassified (feature angle 40°) and remeshed before the
// volume is meshed, since sliver triangles in the input give poor tets otherwise (Gmsh's
// tutorial t13). Everything happens in memory: no file is written, so a failed import leaves
// nothing behind. This folder is its own library group, linked only by the targets that mesh
// surfaces (CMakeLists.txt): the other tools do not load libgmsh.
#include <string>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::meshing {

// `path`: a .obj file (read by mesh::read_obj) or an ASCII or binary .stl file (read by Gmsh).
// `target_edge`: Gmsh's largest element size (Mesh.MeshSizeMax) in file units; 0 keeps Gmsh's
// default. Coordinates are returned in file units. The tets carry the element tags "physical"
// and "region" = 1, like a Gmsh file with one physical volume. InputError naming the file and
// Gmsh's complaint when the surface cannot be read or enclosed by tetrahedra.
mesh::TetMesh volume_from_surface(const std::string& path, double target_edge);

}  // namespace softsim::meshing
