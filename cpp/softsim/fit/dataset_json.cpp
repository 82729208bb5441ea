#include "softsim/fit/dataset_json.hpp"

#include <cstdint>

#include "softsim/io/artifact.hpp"

namespace softsim::fit {

Eigen::MatrixXd read_xyz_rows(const io::JsonReader& array, long expected_rows) {
  const std::size_t n = array.size();
  if (expected_rows >= 0 && n != static_cast<std::size_t>(expected_rows))
    array.fail("an array of " + std::to_string(expected_rows) + " [x, y, z] rows");
  Eigen::MatrixXd m(static_cast<Eigen::Index>(n), 3);
  for (std::size_t i = 0; i < n; ++i) {
    const io::JsonReader row = array[i];
    if (!row.raw().is_array() || row.raw().size() != 3) row.fail("[x, y, z]");
    for (int a = 0; a < 3; ++a) m(static_cast<Eigen::Index>(i), a) = row[a].as_double();
  }
  return m;
}

Dataset dataset_from_json(const io::JsonReader& payload, const std::string& source) {
  Dataset ds;
  ds.source = source;
  const io::JsonReader info = payload.at("dataset");
  ds.kind = info.get_string("kind");
  const std::int64_t count = info.get_int("count");
  // The seed of a random dataset is only provenance here, but a malformed one is still bad input.
  if (info.has("seed") && !info.at("seed").raw().is_null()) info.get_int("seed");

  ds.nodes = read_xyz_rows(payload.at("top_nodes"));
  const long n = static_cast<long>(ds.nodes.rows());
  if (n == 0) payload.at("top_nodes").fail("at least one node");
  const std::int64_t loaded = payload.get_int("loaded_node");
  payload.require(loaded >= 1 && loaded <= n, "loaded_node",
                  "a 1-based node number between 1 and " + std::to_string(n));
  ds.loaded_node = static_cast<int>(loaded - 1);

  const io::JsonReader cases = payload.at("cases");
  if (static_cast<std::int64_t>(cases.size()) != count)
    info.fail_member("count", "the number of cases (" + std::to_string(cases.size()) + ")");
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const io::JsonReader c = cases[i];
    LoadCase lc;
    const auto f = c.get_doubles("force", 3);
    lc.force = Eigen::Vector3d(f[0], f[1], f[2]);
    lc.displacement = read_xyz_rows(c.at("top_displacement"), n);
    ds.cases.push_back(std::move(lc));
  }

  if (payload.has("unit_solutions") && !payload.at("unit_solutions").raw().is_null()) {
    const io::JsonReader units = payload.at("unit_solutions");
    if (!units.raw().is_array() || units.raw().size() != 3) units.fail("three unit-force solutions (x, y, z)");
    Eigen::MatrixXd u(3 * n, 3);
    for (int d = 0; d < 3; ++d) {
      const Eigen::MatrixXd field = read_xyz_rows(units[d], n);
      for (long j = 0; j < n; ++j)
        for (int c = 0; c < 3; ++c) u(3 * j + c, d) = field(j, c);
    }
    ds.unit_solutions = std::move(u);
  }
  if (payload.has("timing")) ds.timing = payload.at("timing").raw();
  return ds;
}

Dataset read_dataset(const std::string& path) {
  const io::Artifact artifact = io::Artifact::read(path, kDatasetSchema, kDatasetSchemaVersion);
  return dataset_from_json(artifact.payload(), path);
}

bool is_dataset_member_ref(const io::JsonReader& node) { return node.raw().is_object() && node.has("artifact"); }

DatasetRef dataset_ref_from_json(const io::JsonReader& node) {
  if (node.raw().is_string()) return {node.as_string(), ""};
  if (!is_dataset_member_ref(node)) node.fail("an rpim_dataset path or {\"artifact\": path, \"member\": name}");
  DatasetRef ref{node.get_string("artifact"), node.get_string("member")};
  node.require(!ref.member.empty(), "member", "the name of a member of the rpim_dataset_set");
  node.reject_unknown();
  return ref;
}

Dataset read_dataset(const DatasetRef& ref) {
  if (ref.member.empty()) return read_dataset(ref.path);
  const io::Artifact artifact = io::Artifact::read(ref.path, kDatasetSetSchema, kDatasetSetSchemaVersion);
  const io::JsonReader members = artifact.payload().at("members");
  if (!members.has(ref.member)) members.fail("a member named \"" + ref.member + "\"");
  return dataset_from_json(members.at(ref.member), ref.label());
}

}  // namespace softsim::fit
