#include "softsim/io/mesh_files.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "softsim/io/atomic_file.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/mesh/gmsh_reader.hpp"
#include "softsim/mesh/surface.hpp"
#include "softsim/mesh/text_tokens.hpp"
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

// Wavefront OBJ -> ASCII STL text (Gmsh reads STL; faces with more than 3 vertices are fanned).
std::string obj_to_stl(const std::string& text, const std::string& source) {
  std::vector<Eigen::Vector3d> v;
  std::vector<mesh::Triangle> faces;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string kind;
    ls >> kind;
    if (kind == "v") {
      Eigen::Vector3d x;
      if (!(ls >> x[0] >> x[1] >> x[2]))
        throw InputError(source + ": line " + std::to_string(line_no) + ": expected \"v x y z\"");
      v.push_back(x);
    } else if (kind == "f") {
      std::vector<int> idx;
      std::string token;
      while (ls >> token) {
        const int i = std::atoi(token.substr(0, token.find('/')).c_str());
        const int resolved = i < 0 ? static_cast<int>(v.size()) + i : i - 1;
        if (resolved < 0 || resolved >= static_cast<int>(v.size()))
          throw InputError(source + ": line " + std::to_string(line_no) +
                           ": expected a vertex index in range, got \"" + token + "\"");
        idx.push_back(resolved);
      }
      if (idx.size() < 3)
        throw InputError(source + ": line " + std::to_string(line_no) + ": expected a face of 3 or more vertices");
      for (std::size_t k = 1; k + 1 < idx.size(); ++k) faces.push_back({idx[0], idx[k], idx[k + 1]});
    }
  }
  if (faces.empty()) throw InputError(source + ": expected a closed triangle surface, got no faces");
  std::ostringstream stl;
  stl.precision(12);
  stl << "solid surface\n";
  for (const auto& f : faces) {
    Eigen::Vector3d n = (v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]);
    if (n.norm() > 0) n.normalize();
    stl << "facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << "\nouter loop\n";
    for (int c = 0; c < 3; ++c) stl << "vertex " << v[f[c]].x() << ' ' << v[f[c]].y() << ' ' << v[f[c]].z() << '\n';
    stl << "endloop\nendfacet\n";
  }
  stl << "endsolid surface\n";
  return stl.str();
}

// Closed surface -> tetrahedral volume through the gmsh command. The surface is first
// reclassified and remeshed (sliver triangles in the input give poor tets otherwise).
mesh::TetMesh mesh_surface_with_gmsh(const std::string& path, const MeshFileOptions& opt) {
  const std::string ext = extension_of(path);
  const std::string text = read_text_file(path);
  // The system's temporary folder (TMPDIR honoured), not a fixed path.
  std::string dir_template = (fs::temp_directory_path() / "softsim-gmsh-XXXXXX").string();
  const char* dir = ::mkdtemp(dir_template.data());
  if (!dir) throw std::runtime_error("cannot create a temporary directory for gmsh");
  const fs::path work(dir);
  const fs::path stl = work / "surface.stl";
  write_file_atomic(stl.string(), ext == ".obj" ? obj_to_stl(text, path) : text);
  std::ostringstream geo;
  geo << "Merge \"surface.stl\";\n"
      << "ClassifySurfaces{40 * Pi / 180, 1, 1, Pi};\n"
      << "CreateGeometry;\n"
      << "Surface Loop(1) = Surface{:};\n"
      << "Volume(1) = {1};\n"
      << "Physical Volume(1) = {1};\n"
      << "Mesh.Algorithm3D = 1;\n"
      << "Mesh.Optimize = 1;\n";
  if (opt.target_edge > 0) geo << "Mesh.MeshSizeMax = " << opt.target_edge << ";\n";
  write_file_atomic((work / "volume.geo").string(), geo.str());
  const std::string cmd = "cd '" + work.string() +
                          "' && gmsh -3 -format msh22 -o volume.msh volume.geo -v 1 > gmsh.log 2>&1";
  const int rc = std::system(cmd.c_str());
  std::string log;
  try { log = read_text_file((work / "gmsh.log").string()); } catch (...) {}
  if (rc != 0 || !fs::exists(work / "volume.msh")) {
    fs::remove_all(work);
    const auto nl = log.find('\n');
    throw InputError(path + ": gmsh could not build a volume mesh from this surface (" +
                     (rc == 127 * 256 || log.find("not found") != std::string::npos
                          ? std::string("gmsh is not installed")
                          : log.substr(0, nl)) + ")");
  }
  mesh::TetMesh m = mesh::read_gmsh(read_text_file((work / "volume.msh").string()), path + " (gmsh volume)");
  fs::remove_all(work);
  return m;
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
    m = mesh_surface_with_gmsh(path, opt);
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
