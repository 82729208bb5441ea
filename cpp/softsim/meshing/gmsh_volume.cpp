#include "softsim/meshing/gmsh_volume.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <unordered_map>

#include <gmsh.h>

#include "softsim/io/atomic_file.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/limits.hpp"
#include "softsim/meshing/bounded_child.hpp"
#include "softsim/mesh/obj_reader.hpp"

namespace softsim::meshing {

namespace {

constexpr int kGmshTriangle = 2;
constexpr int kGmshTet4 = 4;

// One Gmsh session: the API keeps global state, which finalize() releases on every exit path.
// Messages go to Gmsh's logger instead of the terminal (the tools' stdout and stderr stay
// theirs); Gmsh 4.8 reports an error by throwing its message as a std::string.
class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, false);  // no gmshrc: the result must not depend on the user's files
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::logger::start();
  }
  ~GmshSession() {
    gmsh::logger::stop();
    gmsh::finalize();
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  // The last error (or warning) Gmsh logged, for messages that name what went wrong.
  static std::string last_complaint() {
    std::vector<std::string> log;
    gmsh::logger::get(log);
    std::string warning;
    for (auto it = log.rbegin(); it != log.rend(); ++it) {
      if (it->rfind("Error", 0) == 0) return it->substr(it->find(':') + 1);
      if (warning.empty() && it->rfind("Warning", 0) == 0) warning = it->substr(it->find(':') + 1);
    }
    return warning;
  }
};

std::string trimmed(std::string s) {
  const auto b = s.find_first_not_of(" \t\n"), e = s.find_last_not_of(" \t\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// The OBJ surface as a discrete Gmsh surface entity (nodes tagged 1..n, triangles 1..m).
void add_obj_surface(const mesh::TriangleSurface& s) {
  const int tag = gmsh::model::addDiscreteEntity(2);
  std::vector<std::size_t> node_tags(s.vertices.size());
  std::vector<double> coord;
  coord.reserve(3 * s.vertices.size());
  for (std::size_t i = 0; i < s.vertices.size(); ++i) {
    node_tags[i] = i + 1;
    coord.insert(coord.end(), {s.vertices[i].x(), s.vertices[i].y(), s.vertices[i].z()});
  }
  gmsh::model::mesh::addNodes(2, tag, node_tags, coord);
  std::vector<std::size_t> tri;
  tri.reserve(3 * s.triangles.size());
  for (const auto& t : s.triangles)
    for (int v : t) tri.push_back(static_cast<std::size_t>(v) + 1);
  gmsh::model::mesh::addElementsByType(tag, kGmshTriangle, {}, tri);
}

mesh::TetMesh mesh_volume(double target_edge) {
  gmsh::model::mesh::classifySurfaces(40 * M_PI / 180, true, true, M_PI);
  gmsh::model::mesh::createGeometry();
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, 2);
  std::vector<int> tags;
  for (const auto& [dim, tag] : surfaces) tags.push_back(tag);
  const int loop = gmsh::model::geo::addSurfaceLoop(tags);
  const int volume = gmsh::model::geo::addVolume({loop});
  gmsh::model::geo::synchronize();
  gmsh::model::addPhysicalGroup(3, {volume}, 1);
  gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay
  gmsh::option::setNumber("Mesh.Optimize", 1);
  if (target_edge > 0) {
    // A fine target edge meshes for minutes into millions of tetrahedra: estimated from the
    // bounding box (regular tetrahedra of edge h fill it at V / (h^3 / 6 sqrt 2)) and refused
    // over the memory limit before Gmsh starts (about 2 kB a tetrahedron in Gmsh, the mesh and
    // the artifact).
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
    const double box = std::max(x1 - x0, 0.0) * std::max(y1 - y0, 0.0) * std::max(z1 - z0, 0.0);
    const double tets = box / (target_edge * target_edge * target_edge / (6.0 * std::sqrt(2.0)));
    io::require_memory("/source/target_edge", 2000.0 * tets, "the Gmsh volume mesh (about " +
                       std::to_string(static_cast<long long>(std::min(tets, 1e18))) + " tetrahedra)");
    gmsh::option::setNumber("Mesh.MeshSizeMax", target_edge);
  }
  gmsh::model::mesh::generate(3);

  std::vector<std::size_t> node_tags, tet_tags, tet_nodes;
  std::vector<double> coord, parametric;
  gmsh::model::mesh::getNodes(node_tags, coord, parametric, -1, -1, false, false);
  gmsh::model::mesh::getElementsByType(kGmshTet4, tet_tags, tet_nodes);
  mesh::TetMesh m;
  std::unordered_map<std::size_t, int> index_of;
  for (std::size_t i = 0; i < node_tags.size(); ++i) {
    index_of[node_tags[i]] = static_cast<int>(i);
    m.nodes.emplace_back(coord[3 * i], coord[3 * i + 1], coord[3 * i + 2]);
  }
  for (std::size_t e = 0; e < tet_tags.size(); ++e) {
    mesh::Tet t;
    for (int c = 0; c < 4; ++c) t[c] = index_of.at(tet_nodes[4 * e + c]);
    m.tets.push_back(t);
  }
  mesh::drop_unused_nodes(m);
  return m;
}

}  // namespace

mesh::TetMesh volume_from_surface(const std::string& path, double target_edge) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  io::require_input_file(path);  // a regular file of bounded size: Gmsh would read a device for ever
  // Read (and check) an OBJ file before Gmsh starts: its errors name the line.
  const mesh::TriangleSurface obj =
      ext == ".obj" ? mesh::read_obj(io::read_text_file(path), path) : mesh::TriangleSurface();
  // In a child with a time limit (bounded_child.hpp): Gmsh may never finish.
  mesh::TetMesh m = mesh_in_bounded_child([&] {
    GmshSession session;
    mesh::TetMesh volume;
    try {
      gmsh::model::add("surface");
      if (ext == ".obj")
        add_obj_surface(obj);
      else
        gmsh::merge(path);
      gmsh::vectorpair surfaces;
      gmsh::model::getEntities(surfaces, 2);
      if (surfaces.empty()) throw std::string("no triangles in the file");
      volume = mesh_volume(target_edge);
    } catch (const std::string& complaint) {
      throw InputError(path + ": expected a closed triangle surface Gmsh can fill with tetrahedra, got \"" +
                       trimmed(complaint) + "\"");
    }
    if (volume.tets.empty())
      throw InputError(path + ": expected a closed triangle surface Gmsh can fill with tetrahedra, got no tetrahedra (" +
                       trimmed(GmshSession::last_complaint()) + ")");
    return volume;
  });
  // One physical volume, as a Gmsh file with one would carry (the child sends nodes and tets).
  m.element_tags["physical"] = std::vector<int>(m.tets.size(), 1);
  m.element_tags["region"] = m.element_tags["physical"];
  return m;
}

}  // namespace softsim::meshing
