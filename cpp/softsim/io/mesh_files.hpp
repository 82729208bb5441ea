#pragma once
// Loading volume meshes from files: Gmsh .msh (1.0/2.2/4.1), legacy VTK .vtk, and closed
// surfaces (.obj, .stl) that Gmsh turns into a tetrahedral volume.
#include <string>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::io {

struct MeshFileOptions {
  double scale = 1.0;            // unit conversion to metres, applied once here
  double target_edge = 0.0;      // surface meshing only: Gmsh's maximum element size (file units); 0 = Gmsh default
};

// Reads, scales, orients every tet positively, extracts the boundary and adds node sets
// "boundary" and, per physical group p, element tag values. InputError on anything malformed.
mesh::TetMesh load_mesh_file(const std::string& path, const MeshFileOptions& options);

}  // namespace softsim::io
