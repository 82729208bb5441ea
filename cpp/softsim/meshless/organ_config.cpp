#include "softsim/meshless/organ_config.hpp"

#include "softsim/meshless/tet_quadrature.hpp"

namespace softsim::meshless {

OrganScene read_organ_scene(const io::JsonReader& r) {
  OrganScene s;
  if (!r.raw().is_object()) r.fail("an object with \"mesh\" (a tet_mesh artifact)");
  s.mesh_path = r.get_input_path("mesh");
  if (r.has("fixed_sets")) {
    const io::JsonReader sets = r.at("fixed_sets");
    if (!sets.raw().is_array() || sets.size() == 0) sets.fail("a non-empty list of node set names");
    s.fixed_sets.clear();
    for (std::size_t k = 0; k < sets.size(); ++k) s.fixed_sets.push_back(sets[k].as_string());
  }
  if (r.has("loaded_point")) {
    r.require(!r.has("loaded_set"), "loaded_set", "either \"loaded_set\" or \"loaded_point\", not both");
    const auto p = r.get_doubles("loaded_point", 3);
    s.loaded_point = Eigen::Vector3d(p[0], p[1], p[2]);
    s.loaded_set.clear();
  } else {
    s.loaded_set = r.get_string("loaded_set", s.loaded_set);
  }
  s.youngs_modulus = r.get_positive("youngs_modulus", s.youngs_modulus);
  s.poisson_ratio = r.get_double("poisson_ratio", s.poisson_ratio);
  r.require(s.poisson_ratio > -1.0 && s.poisson_ratio < 0.5, "poisson_ratio", "a Poisson ratio in (-1, 0.5)");
  s.tet_rule = r.get_int32("tet_rule", s.tet_rule);
  r.require(is_tet_rule_size(s.tet_rule), "tet_rule", "1, 4 or 5 Gauss points per tetrahedron");
  if (r.has("body_force")) {
    const auto b = r.get_doubles("body_force", 3);
    s.body_force = Eigen::Vector3d(b[0], b[1], b[2]);
  }
  r.reject_unknown();
  return s;
}

nlohmann::json organ_scene_json(const OrganScene& s, const mesh::TetMesh& mesh, const SceneLayout& layout) {
  const TetRule rule = tet_rule(s.tet_rule);
  return {{"mesh", s.mesh_path},
          {"nodes", mesh.num_nodes()},
          {"tets", mesh.num_tets()},
          {"boundary_triangles", mesh.boundary.size()},
          {"surface_nodes", layout.reported_nodes.size()},
          {"surface_node_indices", layout.reported_nodes},
          {"fixed_sets", s.fixed_sets},
          {"loaded_set", s.loaded_point ? nlohmann::json(nullptr) : nlohmann::json(s.loaded_set)},
          {"loaded_point", s.loaded_point ? nlohmann::json{s.loaded_point->x(), s.loaded_point->y(), s.loaded_point->z()}
                                          : nlohmann::json(nullptr)},
          {"loaded_node_index", layout.loaded_node_index},
          {"youngs_modulus", s.youngs_modulus},
          {"poisson_ratio", s.poisson_ratio},
          {"tet_rule", {{"points", s.tet_rule}, {"degree", rule.degree}}},
          {"gauss_points", static_cast<long>(mesh.tets.size() * rule.weights.size())},
          {"body_force", {s.body_force.x(), s.body_force.y(), s.body_force.z()}}};
}

}  // namespace softsim::meshless

namespace softsim::meshless {

std::string organ_mesh_path(const io::JsonReader& config) {
  if (!config.has("organ")) return "";
  const io::JsonReader block = config.at("organ");
  if (!block.raw().is_object()) block.fail("an object with \"mesh\" (a tet_mesh artifact)");
  return block.get_input_path("mesh");
}

}  // namespace softsim::meshless
