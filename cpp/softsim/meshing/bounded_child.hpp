#pragma once
// Gmsh's volume meshing in a child process with a time limit, so that a surface Gmsh never
// finishes (Gmsh 4.8 on some tiny closed surfaces of sharp features only) or a fine target edge
// meshing for hours ends in a one-line input error instead of a run that never ends. The child
// gets the wall-clock limit io::gmsh_timeout_seconds() (SOFTSIM_GMSH_TIMEOUT_S) and, outside
// sanitizer builds, an address-space limit of io::memory_limit_bytes(); it sends the mesh back
// through a pipe. Nothing is written to disk, so a killed child leaves nothing behind.
#include <functional>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::meshing {

// Runs `work` in a forked child and returns its mesh (nodes and tets; element tags are the
// caller's). An InputError of the child is rethrown with its message; a child past the time
// limit or killed otherwise is a ConfigInputError at /source naming the limit.
mesh::TetMesh mesh_in_bounded_child(const std::function<mesh::TetMesh()>& work);

}  // namespace softsim::meshing
