#include "softsim/fit/static_series.hpp"

#include <algorithm>
#include <numeric>

#include "softsim/io/artifact.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/io/result_fields.hpp"

namespace softsim::fit {

StaticSeries static_series_from_json(const io::JsonReader& node) {
  StaticSeries s;
  node.get_choice("kind", {"static_series"});
  s.mesh = node.get_string("mesh");
  s.surface_set = node.get_string("surface_set", s.surface_set);
  const auto p = node.get_doubles("loaded_point", 3);
  s.loaded_point = Eigen::Vector3d(p[0], p[1], p[2]);
  const io::JsonReader cases = node.at("cases");
  if (cases.size() == 0) cases.fail("at least one static solution");
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const io::JsonReader c = cases[i];
    StaticCase sc;
    sc.result = c.get_string("result");
    const auto f = c.get_doubles("force", 3);
    sc.force = Eigen::Vector3d(f[0], f[1], f[2]);
    c.reject_unknown();
    s.cases.push_back(sc);
  }
  node.reject_unknown();
  return s;
}

Dataset read_static_series(const StaticSeries& spec) {
  const mesh::TetMesh mesh = io::read_mesh_artifact(spec.mesh);
  const auto set = mesh.node_sets.find(spec.surface_set);
  if (set == mesh.node_sets.end() || set->second.empty())
    throw InputError(spec.mesh + ": /payload: expected a non-empty node set \"" + spec.surface_set + "\"");
  std::vector<int> surface = set->second;
  // (y, x) order: an n × n grid comes out in the paper's numbering N - 1 = i + n j.
  std::sort(surface.begin(), surface.end(), [&](int a, int b) {
    const Eigen::Vector3d& pa = mesh.nodes[a];
    const Eigen::Vector3d& pb = mesh.nodes[b];
    return pa.y() != pb.y() ? pa.y() < pb.y() : pa.x() < pb.x();
  });
  Dataset ds;
  ds.source = spec.mesh;
  ds.kind = "static_series";
  ds.nodes.resize(static_cast<Eigen::Index>(surface.size()), 3);
  for (std::size_t j = 0; j < surface.size(); ++j) ds.nodes.row(static_cast<Eigen::Index>(j)) = mesh.nodes[surface[j]].transpose();
  Eigen::Index nearest = 0;
  (ds.nodes.rowwise() - spec.loaded_point.transpose()).rowwise().squaredNorm().minCoeff(&nearest);
  ds.loaded_node = static_cast<int>(nearest);
  for (const StaticCase& sc : spec.cases) {
    const std::vector<double> u =
        io::read_nodal_displacements(io::Artifact::read(sc.result, "dhd_result", 1), mesh.num_nodes(), spec.mesh);
    LoadCase lc;
    lc.force = sc.force;
    lc.displacement.resize(ds.nodes.rows(), 3);
    for (std::size_t j = 0; j < surface.size(); ++j)
      for (int c = 0; c < 3; ++c) lc.displacement(static_cast<Eigen::Index>(j), c) = u[3 * static_cast<std::size_t>(surface[j]) + c];
    ds.cases.push_back(std::move(lc));
  }
  return ds;
}

}  // namespace softsim::fit
