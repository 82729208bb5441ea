#include "softsim/fit/surface_playback.hpp"

#include "softsim/fit/dataset_json.hpp"
#include "softsim/fit/evaluation.hpp"
#include "softsim/fit/model_json.hpp"
#include "softsim/fit/playback.hpp"
#include "softsim/fit/report_json.hpp"
#include "softsim/fit/superposition.hpp"
#include "softsim/io/limits.hpp"

namespace softsim::fit {

namespace {

Eigen::Vector3d read_force(const io::JsonReader& node) {
  if (!node.raw().is_array() || node.raw().size() != 3) node.fail("a force [fx, fy, fz] in N");
  return Eigen::Vector3d(node[0].as_double(), node[1].as_double(), node[2].as_double());
}

using NodeRows = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;

}  // namespace

PlaybackConfig read_playback_config(const io::JsonReader& cfg) {
  PlaybackConfig c;
  c.fit_path = cfg.get_string("fit");
  const io::JsonReader forces_node = cfg.at("forces");
  for (std::size_t i = 0; i < forces_node.size(); ++i) c.forces.push_back(read_force(forces_node[i]));
  if (c.forces.empty()) forces_node.fail("at least one force");
  if (cfg.has("reference")) c.reference = dataset_ref_from_json(cfg.at("reference"));
  cfg.reject_unknown();
  return c;
}

void require_same_nodes(const Dataset& ds, const FitModel& model) {
  if (!same_surface(model.nodes, ds.nodes) || ds.loaded_node != model.loaded_node)
    throw InputError(ds.source + ": /payload/top_nodes: expected the surface nodes and loaded node of the fitted datasets");
}

namespace {

Superposition read_playback_reference(const DatasetRef& source, const FitModel& model) {
  Dataset ref = read_dataset(source);
  require_same_nodes(ref, model);
  if (!ref.unit_solutions)
    throw InputError(source.label() + ": /payload/unit_solutions: expected unit solutions for the reference");
  return Superposition(std::move(*ref.unit_solutions));
}

nlohmann::json surface_playback_payload(const std::string& fit_path, const FitModel& model,
                                        const std::vector<Eigen::Vector3d>& forces,
                                        const std::optional<Superposition>& exact) {
  const SurfacePlayer player(model);
  const int n = player.node_count();
  const int l = model.loaded_node;
  // Each case holds its surface displacements (and the reference's error) as JSON values and
  // then as text: about 400 bytes a node (measured: 10.4 kB a force on 25 nodes, the peak memory
  // of 20 000 and 80 000 forces), checked before the first case.
  const double case_bytes = (exact ? 2.0 : 1.0) * 400.0 * n + 1000.0;
  io::require_memory("/forces", case_bytes * static_cast<double>(forces.size()), "the played-back surfaces");
  Eigen::VectorXd u(3 * n), s(3 * n);
  nlohmann::json cases = nlohmann::json::array();
  for (const Eigen::Vector3d& f : forces) {
    player.play(f, u.data());
    const Eigen::MatrixXd rows = NodeRows(u.data(), n, 3);
    const Eigen::Vector3d delta = player.loaded_displacement(f);
    nlohmann::json c = {{"force", {f[0], f[1], f[2]}},
                        {"top_displacement", rows_to_json(rows)},
                        {"loaded_node_displacement", {rows(l, 0), rows(l, 1), rows(l, 2)}},
                        {"relation1_displacement", {delta[0], delta[1], delta[2]}}};
    if (exact) {
      exact->apply(f, s.data());
      const Eigen::MatrixXd ref = NodeRows(s.data(), n, 3);
      ErrorAccumulator e(n);
      e.add(u.data(), ref);
      c["reference_loaded_node_displacement"] = {ref(l, 0), ref(l, 1), ref(l, 2)};
      c["error_vs_reference"] = errors_to_json(e.result());
    }
    cases.push_back(c);
  }
  return {{"fit", fit_path}, {"loaded_node", l + 1}, {"top_nodes", rows_to_json(model.nodes)}, {"cases", cases}};
}

}  // namespace

nlohmann::json play_back(const PlaybackConfig& config) {
  const FitModel model = read_fit_model(config.fit_path);
  std::optional<Superposition> exact;
  if (!config.reference.path.empty()) exact.emplace(read_playback_reference(config.reference, model));
  return surface_playback_payload(config.fit_path, model, config.forces, exact);
}

}  // namespace softsim::fit
