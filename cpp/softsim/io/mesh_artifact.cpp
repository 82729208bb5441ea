#include "softsim/io/mesh_artifact.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "softsim/io/artifact.hpp"

namespace softsim::io {

nlohmann::json mesh_to_json(const mesh::TetMesh& m) {
  nlohmann::json nodes = nlohmann::json::array();
  for (const auto& x : m.nodes) nodes.push_back({x.x(), x.y(), x.z()});
  nlohmann::json tets = nlohmann::json::array();
  for (const auto& t : m.tets) tets.push_back({t[0], t[1], t[2], t[3]});
  nlohmann::json boundary = nlohmann::json::array();
  for (const auto& t : m.boundary) boundary.push_back({t[0], t[1], t[2]});
  nlohmann::json sets = nlohmann::json::object();
  for (const auto& [name, s] : m.node_sets) sets[name] = s;
  nlohmann::json tags = nlohmann::json::object();
  for (const auto& [name, s] : m.element_tags) tags[name] = s;
  return {{"units", "m"}, {"nodes", nodes}, {"tets", tets}, {"boundary", boundary},
          {"node_sets", sets}, {"element_tags", tags}};
}

nlohmann::json quality_to_json(const mesh::QualityReport& r) {
  return {{"nodes", r.nodes},
          {"tets", r.tets},
          {"boundary_triangles", r.boundary_triangles},
          {"total_volume", r.total_volume},
          {"min_volume", r.min_volume},
          {"max_volume", r.max_volume},
          {"min_dihedral_deg", r.min_dihedral_deg},
          {"max_dihedral_deg", r.max_dihedral_deg},
          {"min_altitude", r.min_altitude},
          {"min_edge", r.min_edge},
          {"max_edge", r.max_edge},
          {"sliver_threshold_deg", r.sliver_threshold_deg},
          {"sliver_count", r.slivers.size()},
          {"slivers", r.slivers}};
}

mesh::TetMesh mesh_from_json(const JsonReader& payload) {
  mesh::TetMesh m;
  const std::string units = payload.get_string("units");
  if (units != "m") payload.at("units").fail("\"m\" (artifacts are SI)");
  const JsonReader nodes = payload.at("nodes");
  const std::size_t n = nodes.size();
  if (n == 0) nodes.fail("a non-empty array of nodes");
  m.nodes.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const JsonReader p = nodes[i];
    if (p.size() != 3) p.fail("[x, y, z]");
    for (int c = 0; c < 3; ++c) m.nodes[i][c] = p[static_cast<std::size_t>(c)].as_double();
  }
  auto read_index = [&](const JsonReader& r) {
    const auto v = r.as_int();
    if (v < 0 || v >= static_cast<std::int64_t>(n))
      r.fail("a node index in [0, " + std::to_string(n - 1) + "]");
    return static_cast<int>(v);
  };
  const JsonReader tets = payload.at("tets");
  if (tets.size() == 0) tets.fail("a non-empty array of tetrahedra");
  m.tets.resize(tets.size());
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    const JsonReader t = tets[e];
    if (t.size() != 4) t.fail("4 node indices");
    for (int c = 0; c < 4; ++c) m.tets[e][c] = read_index(t[static_cast<std::size_t>(c)]);
    auto sorted = m.tets[e];
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      t.fail("4 distinct node indices");
    const double v = mesh::signed_volume(m, m.tets[e]);
    if (!(v > 0)) {
      std::ostringstream vol;
      vol << std::scientific << std::setprecision(3) << v;
      t.fail("a positively oriented tetrahedron (volume " + vol.str() + " m^3)");
    }
  }
  // A node of no tetrahedron has no mass and no stiffness: the static solve would call the
  // model singular. mesher drops such nodes on import, so one here is a damaged artifact.
  const std::vector<char> used = mesh::nodes_in_tets(m);
  for (std::size_t i = 0; i < n; ++i)
    if (!used[i]) nodes[i].fail("a node of at least one tetrahedron");
  const JsonReader boundary = payload.at("boundary");
  m.boundary.resize(boundary.size());
  for (std::size_t f = 0; f < m.boundary.size(); ++f) {
    const JsonReader t = boundary[f];
    if (t.size() != 3) t.fail("3 node indices");
    for (int c = 0; c < 3; ++c) m.boundary[f][c] = read_index(t[static_cast<std::size_t>(c)]);
  }
  const JsonReader sets = payload.at("node_sets");
  for (const auto& name : sets.keys()) {
    const JsonReader s = sets.at(name);
    std::vector<int> ids(s.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = read_index(s[i]);
    m.node_sets[name] = std::move(ids);
  }
  const JsonReader tags = payload.at("element_tags");
  for (const auto& name : tags.keys()) {
    const JsonReader s = tags.at(name);
    if (s.size() != m.tets.size())
      s.fail("one tag per tetrahedron (" + std::to_string(m.tets.size()) + ")");
    std::vector<int> values(s.size());
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = s[i].as_int32();
    m.element_tags[name] = std::move(values);
  }
  payload.accept("quality");
  payload.accept("source");
  payload.reject_unknown();
  return m;
}

mesh::TetMesh read_mesh_artifact(const std::string& path) {
  const Artifact a = Artifact::read(path, kMeshSchema, kMeshSchemaVersion);
  return mesh_from_json(a.payload());
}

}  // namespace softsim::io
