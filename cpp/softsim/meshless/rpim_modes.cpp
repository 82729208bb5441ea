#include "softsim/meshless/rpim_modes.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "softsim/io/limits.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/meshless/lee_radok.hpp"
#include "softsim/meshless/organ_config.hpp"
#include "softsim/meshless/plate_dataset.hpp"
#include "softsim/meshless/result_json.hpp"
#include "softsim/meshless/rpim_config.hpp"

namespace softsim::meshless {

namespace {

RpimSettings read_settings(const io::JsonReader& cfg) {
  return read_rpim_settings(cfg.optional("rpim"), cfg.optional("penalty"), cfg.optional("solver"));
}

nlohmann::json indentation_json(const IndentationInputs& in, double scene_modulus) {
  const IndentationModulus m = lee_radok_modulus(in.force, in.depth, in.probe_radius, in.poisson_ratio);
  return {{"force", in.force},
          {"depth", in.depth},
          {"probe_radius", in.probe_radius},
          {"poisson_ratio", in.poisson_ratio},
          {"shear_modulus", m.shear_modulus},
          {"youngs_modulus", m.youngs_modulus},
          {"scene_youngs_modulus", scene_modulus},
          {"ratio_to_scene", m.youngs_modulus / scene_modulus}};
}

// One dataset ("dataset": {...}) or several of one model ("datasets": {name: {...}}): the
// latter builds and factors the plate once and writes an "rpim_dataset_set" whose members are
// the payloads the single runs would write (timings aside).
RpimOutput run_dataset(const io::JsonReader& cfg) {
  // The scene: the paper's plate (002 §4.1) or an organ mesh (002 §5.3), not both.
  const bool organ = cfg.has("organ");
  if (organ && cfg.has("plate")) cfg.fail_member("organ", "either \"plate\" or \"organ\", not both");
  const PlateScene scene = read_plate_scene(cfg.optional("plate"));
  std::optional<OrganScene> organ_scene;
  if (organ) organ_scene = read_organ_scene(cfg.at("organ"));
  const RpimSettings settings = read_settings(cfg);
  const bool several = cfg.has("datasets");
  if (several && cfg.has("dataset"))
    cfg.fail_member("datasets", "either \"dataset\" (one force set) or \"datasets\" (named sets), not both");
  std::vector<std::string> names;
  std::vector<DatasetSpec> specs;
  if (several) {
    const io::JsonReader sets = cfg.at("datasets");
    if (!sets.raw().is_object() || sets.raw().empty()) sets.fail("an object of named dataset specs");
    for (const auto& [name, value] : sets.raw().items()) {
      names.push_back(name);
      specs.push_back(read_dataset_spec(sets.at(name)));
    }
  } else {
    specs.push_back(read_dataset_spec(cfg.at("dataset")));
  }
  const DatasetOutput output = read_dataset_output(cfg.optional("output"));
  const bool all_nodes = output.all_nodes, stiffness_conditioning = output.stiffness_conditioning;
  std::optional<IndentationInputs> indentation;
  if (const auto ind = cfg.optional("indentation")) indentation = read_indentation(*ind);
  cfg.reject_unknown();

  MeshlessProblem problem;
  SceneLayout layout;
  nlohmann::json scene_json;
  if (organ_scene) {
    const mesh::TetMesh mesh = io::read_mesh_artifact(organ_scene->mesh_path);
    layout = organ_layout(*organ_scene, mesh);
    problem = organ_problem(*organ_scene, mesh);
    scene_json = organ_scene_json(*organ_scene, mesh, layout);
  } else {
    problem = plate_problem(scene);
    layout = plate_layout(scene);
    scene_json = plate_scene_json(scene);
  }
  const double scene_modulus = problem.youngs_modulus;
  // Memory, estimated before anything is assembled: a dense factorisation holds the 3N x 3N
  // stiffness and its factor; every case writes 3 displacements of each node it reports as
  // JSON values and text (about 60 bytes a number).
  const double nodes = static_cast<double>(problem.nodes.size());
  if (settings.solver == SolverKind::dense_llt)
    io::require_memory("/solver", 2.0 * (3.0 * nodes) * (3.0 * nodes) * 8.0, "the dense stiffness and its factor");
  const double reported = all_nodes ? nodes : static_cast<double>(layout.reported_nodes.size());
  double cases_reported = 0;
  for (const auto& spec : specs) cases_reported += std::max(spec.count, 1);
  io::require_memory(several ? "/datasets" : "/dataset", cases_reported * reported * 3.0 * 60.0,
                     "the displacements of every case");

  std::vector<std::vector<Eigen::Vector3d>> force_sets;
  for (const auto& spec : specs) force_sets.push_back(dataset_forces(spec));
  const std::vector<SceneRun> runs = run_scene_sets(problem, layout, settings, force_sets, stiffness_conditioning);
  std::vector<nlohmann::json> payloads;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    payloads.push_back(dataset_payload(organ ? "organ" : "plate", scene_json, settings, specs[k], runs[k], all_nodes));
    if (indentation) payloads.back()["indentation"] = indentation_json(*indentation, scene_modulus);
  }

  const SceneRun& run = runs.front();
  const int l = run.loaded_node_index;
  const double build_s = run.timings.total_s - run.timings.solves_s;
  double solves_s = 0;
  int cases = 0;
  for (const auto& r : runs) {
    cases += static_cast<int>(r.forces.size());
    solves_s += r.timings.solves_s;
  }
  std::ostringstream summary;
  summary << run.nodes.size() << " nodes, " << runs.size() << (several ? " datasets, " : " dataset, ") << cases
          << " cases; node " << run.loaded_node_number << " compliance (" << run.unit_solutions(3 * l, 0) << ", "
          << run.unit_solutions(3 * l + 1, 1) << ", " << run.unit_solutions(3 * l + 2, 2) << ") m/N; "
          << build_s + solves_s << " s";
  if (!several) {
    RpimOutput out{"rpim_dataset", std::move(payloads.front()), std::nullopt, summary.str()};
    if (specs.front().kind == DatasetKind::random) out.seed = specs.front().seed;
    return out;
  }
  nlohmann::json members = nlohmann::json::object();
  std::optional<std::uint64_t> seed;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    members[names[k]] = std::move(payloads[k]);
    if (specs[k].kind == DatasetKind::random && !seed) seed = specs[k].seed;  // the first random set's
  }
  nlohmann::json payload = {{"members", std::move(members)},
                            {"timing", {{"build_s", build_s},
                                        {"solves_s", solves_s},
                                        {"total_s", build_s + solves_s},
                                        {"conditioning_s", run.timings.conditioning_s},
                                        {"datasets", runs.size()},
                                        {"cases_solved", cases + 3 * static_cast<int>(runs.size())}}}};
  return {"rpim_dataset_set", std::move(payload), seed, summary.str()};
}

RpimOutput run_stability(const io::JsonReader& cfg) {
  const PlateScene scene = read_plate_scene(cfg.optional("plate"));
  const RpimSettings settings = read_settings(cfg);
  const io::JsonReader sweep = cfg.at("stability");
  cfg.reject_unknown();
  std::vector<std::pair<StabilityParameter, double>> runs;
  for (const StabilityParameter parameter : kStabilityParameters) {
    const std::string key = stability_parameter_name(parameter);
    if (!sweep.has(key)) continue;
    for (double v : sweep.get_doubles(key)) {
      sweep.require(v > 0, key, "positive parameter values");
      if (parameter == StabilityParameter::nearest_count)
        sweep.require(v >= 1 && v <= 1000 && v == std::floor(v), key, "whole node counts between 1 and 1000");
      runs.emplace_back(parameter, v);
    }
  }
  sweep.reject_unknown();
  if (runs.empty()) sweep.fail("at least one parameter list (q, alpha_c, d_c_spacing_factor, ...)");

  nlohmann::json points = nlohmann::json::array();
  int failures = 0;
  for (const auto& [parameter, value] : runs) {
    const StabilityPoint p = stability_point(scene, settings, parameter, value);
    failures += p.ok ? 0 : 1;
    points.push_back(stability_point_json(p, settings.max_moment_condition));
  }
  const double h = plate_mean_spacing(scene);
  nlohmann::json payload = {
      {"plate", plate_scene_json(scene)},
      {"base", rpim_settings_json(settings, resolve_rbf(settings, h), resolve_support(settings, h), h)},
      {"loaded_node", plate_loaded_node_number(scene)},
      {"points", points}};
  return {"rpim_stability", std::move(payload), std::nullopt,
          std::to_string(runs.size()) + " settings, " + std::to_string(failures) + " numerical failures (recorded)"};
}

RpimOutput run_convergence(const io::JsonReader& cfg) {
  const BlockStudy block = read_block_study(cfg.optional("block"));
  const RpimSettings settings = read_settings(cfg);
  std::vector<int> counts;
  for (const auto n : cfg.get_ints("nodes_per_edge")) {
    cfg.require(n >= 3 && n <= 41, "nodes_per_edge", "node counts per edge between 3 and 41");
    counts.push_back(static_cast<int>(n));
  }
  cfg.require(!counts.empty() && counts.size() <= 64, "nodes_per_edge", "a list of 1 to 64 node counts per edge");
  const double nodes = std::pow(*std::max_element(counts.begin(), counts.end()), 3.0);
  if (settings.solver == SolverKind::dense_llt) {
    io::require_memory(cfg, "nodes_per_edge", 2.0 * (3.0 * nodes) * (3.0 * nodes) * 8.0,
                       "the dense stiffness and its factor of the finest block");
  } else {
    // The sparse path (shape functions, stiffness, its factor, the reference) took 320 kB a
    // node at 9 nodes per edge and over 360 kB at 13 (peak memory): 400 kB a node is checked.
    io::require_memory(cfg, "nodes_per_edge", 400e3 * nodes, "the finest block's shape functions, stiffness and factor");
  }
  cfg.reject_unknown();

  const std::vector<ConvergencePoint> study = convergence_study(block, settings, counts);
  nlohmann::json rows = nlohmann::json::array();
  std::vector<double> h, rms, max;
  for (const auto& p : study) {
    rows.push_back({{"nodes_per_edge", p.nodes_per_edge},
                    {"nodes", p.result.nodes},
                    {"spacing", p.result.spacing},
                    {"rms_error", p.result.rms_error},
                    {"max_error", p.result.max_error},
                    {"reference", p.result.reference},
                    {"relative_rms_error", p.result.relative_rms()},
                    {"relative_max_error", p.result.relative_max()}});
    h.push_back(p.result.spacing);
    rms.push_back(p.result.rms_error);
    max.push_back(p.result.max_error);
  }
  const double edge_h = block.edge / (counts.front() - 1);
  nlohmann::json payload = {
      {"block",
       {{"field", block.field == ManufacturedField::plane_wave ? "plane_wave" : "linear_patch"},
        {"edge", block.edge},
        {"youngs_modulus", block.youngs_modulus},
        {"poisson_ratio", block.poisson_ratio},
        {"gauss_order", block.gauss_order},
        {"boundary", "every boundary node held at the exact displacement by penalty"}}},
      {"model", rpim_settings_json(settings, resolve_rbf(settings, edge_h), resolve_support(settings, edge_h), edge_h)},
      {"rows", rows},
      {"observed_rate", {{"rms", observed_rate(h, rms)}, {"max", observed_rate(h, max)}}}};
  payload["model"]["note"] = "spacing-relative lengths resolved with the first refinement's spacing";
  std::ostringstream summary;
  summary << "observed rate (rms) " << observed_rate(h, rms);
  return {"rpim_convergence", std::move(payload), std::nullopt, summary.str()};
}

}  // namespace

RpimOutput run_rpim_mode(const std::string& mode, const io::JsonReader& config) {
  if (mode == "stability") return run_stability(config);
  if (mode == "convergence") return run_convergence(config);
  if (mode == "dataset") return run_dataset(config);
  throw InputError("unknown rpim_precompute mode \"" + mode + "\": expected dataset, stability or convergence");
}

}  // namespace softsim::meshless
