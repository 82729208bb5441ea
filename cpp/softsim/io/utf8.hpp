#pragma once
// Names read from input files (a VTU DataArray's Name, a VTK array name, a Gmsh physical name)
// become JSON keys of the artifact, and JSON text is UTF-8: a name that is not would make the
// artifact unwritable at the very end of a run (an internal error). Checked where a file enters.
#include <cstddef>
#include <string>

namespace softsim::io {

// Offset of the first byte of `text` that does not begin or continue a well-formed UTF-8
// sequence (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF), or npos.
std::size_t first_invalid_utf8(const std::string& text);

}  // namespace softsim::io
