#pragma once
// VTK XML UnstructuredGrid (.vtu) reader for the files io/vtu_writer.hpp writes, and for any
// uncompressed VTU of one piece: ASCII arrays, inline base64 arrays (format="binary") and raw
// appended data, with a UInt32 or UInt64 byte-count header, in either byte order. Keeps the
// VTK_TETRA cells; integer one-component cell arrays become element tags of the same name (as
// in the legacy reader). Compressed files and base64-encoded appended data are refused by name.
#include <string>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::mesh {

// `bytes`: the whole file; `source` names it in error messages.
TetMesh read_vtu(const std::string& bytes, const std::string& source);

}  // namespace softsim::mesh
