#include "softsim/hybrid/tool_config.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/limits.hpp"
#include "softsim/io/surface_files.hpp"
#include "softsim/mesh/surface.hpp"

namespace softsim::hybrid {

namespace {

constexpr double kBytesPerToolTriangle = 600;

// A mesh tool's "file" (× "scale", file units to metres, then turned by "rotation" about the
// frame's origin) as a closed surface; a bad file is bad input at /.../file, one line naming the
// config, the member and what is wrong with the file.
std::shared_ptr<const mesh::ClosedSurface> read_tool_surface(const io::JsonReader& t) {
  const std::string path = t.get_input_path("file");
  const double scale = t.get_positive("scale", 1.0);
  Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
  if (auto r = t.optional("rotation")) {
    const Eigen::Vector3d axis = read_vec3(*r, "axis");
    r->require(axis.norm() > 0, "axis", "a non-zero rotation axis");
    const double degrees = r->get_double("degrees");
    r->require(std::isfinite(degrees), "degrees", "a finite angle in degrees");
    r->reject_unknown();
    turn = Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
  }
  mesh::TriangleSurface s;
  try {
    s = io::read_surface_file(path, scale);
  } catch (const InputError& e) {
    throw InputError(t.file() + ": " + t.at("file").pointer() + ": " + e.what());
  }
  // The closed surface and the tool's search structures take about 580 bytes a triangle
  // (measured: 99 500 and 399 000 triangles of a binary STL, peak memory of a dhd_sim run):
  // checked before they are built.
  io::require_memory(t, "file", kBytesPerToolTriangle * static_cast<double>(s.triangles.size()),
                     "the mesh tool's surface and search structures (" + std::to_string(s.triangles.size()) + " triangles)");
  try {
    for (auto& v : s.vertices) v = turn * v;
    return std::make_shared<const mesh::ClosedSurface>(std::move(s), path);
  } catch (const InputError& e) {
    throw InputError(t.file() + ": " + t.at("file").pointer() + ": " + e.what());
  }
}

}  // namespace

std::vector<dynamics::RigidTool> read_tools(const io::JsonReader& boundary, const mesh::TetMesh& mesh) {
  std::vector<dynamics::RigidTool> tools;
  auto list = boundary.optional("tools");
  if (!list) return tools;
  std::vector<int> surface;  // the boundary nodes, found once when a tool needs them
  for (std::size_t i = 0; i < list->size(); ++i) {
    const io::JsonReader t = (*list)[i];
    dynamics::RigidTool tool;
    const std::string shape = t.get_choice("shape", {"sphere", "capsule", "plane", "mesh"});
    tool.name = t.get_string("name", shape + "[" + std::to_string(i) + "]");
    if (shape == "mesh") {
      tool.shape = dynamics::RigidTool::Shape::mesh;
      tool.surface = read_tool_surface(t);
    } else if (shape == "plane") {
      tool.shape = dynamics::RigidTool::Shape::plane;
      const Eigen::Vector3d n = read_vec3(t, "normal");
      t.require(n.norm() > 0, "normal", "a non-zero normal (pointing out of the tool, into the body)");
      tool.normal = n.normalized();
    } else {
      tool.shape = shape == "sphere" ? dynamics::RigidTool::Shape::sphere : dynamics::RigidTool::Shape::capsule;
      tool.radius = t.get_positive("radius");
      if (tool.shape == dynamics::RigidTool::Shape::capsule) {
        const Eigen::Vector3d axis = read_vec3(t, "axis");
        t.require(axis.norm() > 0, "axis", "a non-zero segment (from one end of the capsule's axis to the other)");
        tool.half_axis = 0.5 * axis;
      }
    }
    tool.start = read_vec3(t, "position");
    tool.travel = t.has("travel") ? read_vec3(t, "travel") : Eigen::Vector3d::Zero();
    tool.ramp = read_ramp(t);
    if (t.has("search_margin")) tool.search_margin = t.get_positive("search_margin");
    tool.friction = t.get_double("friction", tool.friction);
    t.require(tool.friction >= 0, "friction", "a Coulomb friction coefficient >= 0");
    if (t.has("nodes")) {
      const std::string set = t.get_string("nodes");
      const auto it = mesh.node_sets.find(set);
      if (it == mesh.node_sets.end() || it->second.empty())
        t.fail_member("nodes", "the name of a non-empty node set of the mesh");
      tool.nodes = it->second;
    } else {
      if (surface.empty()) {
        if (!mesh.boundary.empty()) {
          surface = mesh::boundary_nodes(mesh);
        } else {  // a mesh read without its surface: the faces used by one element
          for (const auto& tri : mesh::extract_boundary(mesh, "mesh"))
            surface.insert(surface.end(), tri.begin(), tri.end());
          std::sort(surface.begin(), surface.end());
          surface.erase(std::unique(surface.begin(), surface.end()), surface.end());
        }
      }
      tool.nodes = surface;
    }
    for (int node : tool.nodes) tool.positions.push_back(mesh.nodes[node]);
    t.reject_unknown();
    tools.push_back(std::move(tool));
  }
  return tools;
}

}  // namespace softsim::hybrid
