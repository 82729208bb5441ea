#include "softsim/io/mesh_files.hpp"

#include <cstdio>
#include <filesystem>

#include "softsim/io/atomic_file.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/utf8.hpp"
#include "softsim/mesh/gmsh_reader.hpp"
#include "softsim/mesh/surface.hpp"
#include "softsim/mesh/vtk_legacy_reader.hpp"
#include "softsim/mesh/vtu_reader.hpp"

namespace softsim::io {

namespace fs = std::filesystem;

namespace {

// Every tag and node-set name a file gave is UTF-8 (utf8.hpp): the artifact's keys.
void require_utf8_names(const mesh::TetMesh& m, const std::string& path) {
  for (const auto* names : {&m.element_tags, &m.node_sets})
    for (const auto& entry : *names)
      if (const std::size_t at = first_invalid_utf8(entry.first); at != std::string::npos) {
        char byte[8];
        std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(entry.first[at]));
        throw InputError(path + ": expected array and set names in UTF-8, got a name with the byte " + byte +
                         " at offset " + std::to_string(at));
      }
}

std::string extension_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

mesh::TetMesh load_mesh_file(const std::string& path, const MeshFileOptions& opt) {
  if (!fs::exists(path)) throw InputError(path + ": cannot open file");
  if (!(opt.scale > 0)) throw InputError(path + ": expected a positive scale");
  const std::string ext = extension_of(path);
  mesh::TetMesh m;
  if (ext == ".msh") {
    m = mesh::read_gmsh(read_text_file(path), path);
  } else if (ext == ".vtk") {
    m = mesh::read_vtk_legacy(read_text_file(path), path);
  } else if (ext == ".vtu") {
    m = mesh::read_vtu(read_text_file(path), path);
  } else if (ext == ".obj" || ext == ".stl") {
    if (!opt.surface_mesher)
      throw InputError(path + ": expected a volume mesh (this program cannot mesh .obj/.stl surfaces; mesher can)");
    m = opt.surface_mesher(path, opt.target_edge);
  } else {
    throw InputError(path + ": expected a mesh file (.msh, .vtk, .vtu, .obj or .stl), got extension \"" + ext + "\"");
  }
  require_utf8_names(m, path);
  mesh::scale(m, opt.scale);
  mesh::orient_positively(m, path);
  m.boundary = mesh::extract_boundary(m, path);
  m.node_sets["boundary"] = mesh::boundary_nodes(m);
  return m;
}

}  // namespace softsim::io
