#pragma once
// Loading volume meshes from files: Gmsh .msh (1.0 ASCII, 2.2 and 4.1 ASCII or binary), legacy
// VTK .vtk, VTK XML .vtu, and closed surfaces (.obj, .stl) that a surface mesher turns into a
// tetrahedral volume.
#include <functional>
#include <string>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::io {

struct MeshFileOptions {
  double scale = 1.0;            // unit conversion to metres, applied once here
  double target_edge = 0.0;      // surface meshing only: Gmsh's maximum element size (file units); 0 = Gmsh default
  // Closed surface file -> volume mesh in file units (meshing::volume_from_surface, which needs
  // libgmsh: the tools that mesh surfaces set it). Without it .obj and .stl files are refused.
  std::function<mesh::TetMesh(const std::string& path, double target_edge)> surface_mesher;
};

// Reads, scales, orients every tet positively, extracts the boundary and adds node sets
// "boundary" and, per physical group p, element tag values. InputError on anything malformed.
mesh::TetMesh load_mesh_file(const std::string& path, const MeshFileOptions& options);

}  // namespace softsim::io
