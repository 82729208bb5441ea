#include "softsim/io/mesh_files.hpp"

#include <filesystem>

#include "softsim/io/atomic_file.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/mesh/gmsh_reader.hpp"
#include "softsim/mesh/surface.hpp"
#include "softsim/mesh/vtk_legacy_reader.hpp"
#include "softsim/mesh/vtu_reader.hpp"

namespace softsim::io {

namespace fs = std::filesystem;

namespace {

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
  mesh::scale(m, opt.scale);
  mesh::orient_positively(m, path);
  m.boundary = mesh::extract_boundary(m, path);
  m.node_sets["boundary"] = mesh::boundary_nodes(m);
  return m;
}

}  // namespace softsim::io
