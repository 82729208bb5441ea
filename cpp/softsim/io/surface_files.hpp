#pragma once
// Closed triangle surfaces from files, for a rigid instrument of any shape: STL (ASCII or
// binary; what CAD systems and 3-D scanners export) and Wavefront OBJ (what modelling tools
// export). A VTU/VTK surface is not taken: an instrument rarely comes as one.
#include <string>

#include "softsim/mesh/obj_reader.hpp"

namespace softsim::io {

// By extension (.stl, .obj; any case), coordinates × `scale` (file units to metres).
// InputError naming the file for a missing or unreadable file, another extension, or malformed
// content.
mesh::TriangleSurface read_surface_file(const std::string& path, double scale = 1.0);

}  // namespace softsim::io
