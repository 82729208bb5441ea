#pragma once
// STL surfaces, the format CAD systems and 3-D printing export an instrument in: binary (80-byte
// header, triangle count, 50 bytes per triangle) or ASCII ("solid ... facet normal ... outer
// loop vertex x y z ... endloop endfacet ... endsolid"). STL stores every triangle with its own
// three corners, so corners with equal coordinates are welded into one vertex (exactly equal:
// an exporter writes a shared corner with the same digits). The facet normals are ignored; the
// orientation comes from the corner order.
#include <string>

#include "softsim/mesh/obj_reader.hpp"

namespace softsim::mesh {

// `bytes`: the whole file. Binary when its size is 84 + 50 × (the count at byte 80), ASCII
// otherwise (a binary header may begin with "solid" too). InputError naming `source` (and the
// line, for ASCII) for a malformed or non-finite corner, a truncated file or no triangles.
TriangleSurface read_stl(const std::string& bytes, const std::string& source);

}  // namespace softsim::mesh
