#include "softsim/meshless/organ_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "softsim/io/errors.hpp"
#include "softsim/mesh/surface.hpp"
#include "softsim/meshless/tet_quadrature.hpp"

namespace softsim::meshless {

namespace {

const std::vector<int>& node_set(const OrganScene& scene, const mesh::TetMesh& mesh, const std::string& name,
                                 const std::string& pointer) {
  const auto it = mesh.node_sets.find(name);
  if (it == mesh.node_sets.end() || it->second.empty())
    throw ConfigInputError(pointer, "the name of a non-empty node set of the mesh " + scene.mesh_path +
                                        " (it has no \"" + name + "\")");
  return it->second;
}

std::vector<int> fixed_nodes(const OrganScene& scene, const mesh::TetMesh& mesh) {
  std::vector<int> fixed;
  for (std::size_t k = 0; k < scene.fixed_sets.size(); ++k) {
    const auto& set = node_set(scene, mesh, scene.fixed_sets[k], "/organ/fixed_sets/" + std::to_string(k));
    fixed.insert(fixed.end(), set.begin(), set.end());
  }
  std::sort(fixed.begin(), fixed.end());
  fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
  return fixed;
}

}  // namespace

double organ_mean_spacing(const mesh::TetMesh& mesh) {
  double volume = 0;
  for (const auto& t : mesh.tets) volume += std::abs(mesh::signed_volume(mesh, t));
  return std::cbrt(volume / static_cast<double>(mesh.nodes.size()));
}

MeshlessProblem organ_problem(const OrganScene& scene, const mesh::TetMesh& mesh) {
  MeshlessProblem p;
  p.nodes = mesh.nodes;
  p.quadrature = tet_quadrature(mesh, tet_rule(scene.tet_rule));
  p.youngs_modulus = scene.youngs_modulus;
  p.poisson_ratio = scene.poisson_ratio;
  for (const auto& [name, set] : mesh.node_sets)
    if (std::find(scene.fixed_sets.begin(), scene.fixed_sets.end(), name) != scene.fixed_sets.end())
      for (int n : set) p.constraints.push_back({n, Eigen::Vector3d::Zero()});
  std::sort(p.constraints.begin(), p.constraints.end(), [](const auto& a, const auto& b) { return a.node < b.node; });
  p.constraints.erase(std::unique(p.constraints.begin(), p.constraints.end(),
                                  [](const auto& a, const auto& b) { return a.node == b.node; }),
                      p.constraints.end());
  p.mean_spacing = organ_mean_spacing(mesh);
  return p;
}

SceneLayout organ_layout(const OrganScene& scene, const mesh::TetMesh& mesh) {
  SceneLayout l;
  l.reported_nodes = mesh::boundary_nodes(mesh);
  if (l.reported_nodes.empty())
    throw ConfigInputError("/organ/mesh", "a mesh with boundary triangles (" + scene.mesh_path + " has none)");
  l.fixed_nodes = fixed_nodes(scene, mesh);
  const std::string pointer = scene.loaded_point ? "/organ/loaded_point" : "/organ/loaded_set";
  if (scene.loaded_point) {
    // The nearest surface node, the lowest index on ties.
    double best = std::numeric_limits<double>::infinity();
    for (int n : l.reported_nodes) {
      const double d = (mesh.nodes[n] - *scene.loaded_point).norm();
      if (d < best) best = d, l.loaded_node_index = n;
    }
  } else {
    const auto& loaded = node_set(scene, mesh, scene.loaded_set, pointer);
    if (loaded.size() != 1)
      throw ConfigInputError(pointer, "a node set of exactly one node (\"" + scene.loaded_set + "\" holds " +
                                          std::to_string(loaded.size()) + ")");
    l.loaded_node_index = loaded.front();
  }
  const auto pos = std::lower_bound(l.reported_nodes.begin(), l.reported_nodes.end(), l.loaded_node_index);
  if (pos == l.reported_nodes.end() || *pos != l.loaded_node_index)
    throw ConfigInputError(pointer, "a surface node (node " + std::to_string(l.loaded_node_index) +
                                                    " of \"" + scene.loaded_set + "\" is inside the mesh)");
  if (std::binary_search(l.fixed_nodes.begin(), l.fixed_nodes.end(), l.loaded_node_index))
    throw ConfigInputError(pointer, "a node that no fixed set holds (node " +
                                                    std::to_string(l.loaded_node_index) + " is fixed)");
  l.loaded_node_number = static_cast<int>(pos - l.reported_nodes.begin()) + 1;
  l.body_force = scene.body_force;
  return l;
}

}  // namespace softsim::meshless
