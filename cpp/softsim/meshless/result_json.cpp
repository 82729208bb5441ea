#include "softsim/meshless/result_json.hpp"

#include <cmath>

#include "softsim/meshless/rpim_config.hpp"

#ifdef SOFTSIM_HAVE_OPENMP
#include <omp.h>
#endif

namespace softsim::meshless {

namespace {

nlohmann::json vec3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json node_displacements(const Eigen::VectorXd& u, const std::vector<int>& nodes) {
  nlohmann::json out = nlohmann::json::array();
  for (int n : nodes) out.push_back(vec3(u.segment<3>(3 * n)));
  return out;
}

nlohmann::json spectrum_json(const SpectrumEstimate& s) {
  return {{"lambda_min", s.lambda_min}, {"lambda_max", s.lambda_max}, {"condition", s.condition},
          {"iterations", s.iterations}};
}

int thread_count() {
#ifdef SOFTSIM_HAVE_OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

}  // namespace

nlohmann::json conditioning_json(const PlateConditioning& c, double max_moment_condition) {
  nlohmann::json j = {
      {"moment_matrix",
       {{"condition_min", c.moment.min_condition},
        {"condition_median", c.moment.median_condition},
        {"condition_max", c.moment.max_condition},
        {"condition_limit", max_moment_condition},
        {"estimate", "1-norm, LU reciprocal condition estimate"}}},
      {"support_nodes", {{"min", c.moment.min_support}, {"mean", c.moment.mean_support}, {"max", c.moment.max_support}}},
      {"gauss_points", c.moment.points},
      {"shape_consistency",
       {{"partition_of_unity_error", c.moment.partition_error},
        {"linear_reproduction_error", c.moment.linear_error},
        {"gradient_reproduction_error", c.moment.gradient_error}}},
      {"rigid_mode_energy", {{"max_ratio", c.rigid_modes.max_ratio}, {"modes", c.rigid_modes.ratio}}},
      {"factorisation_pivot_ratio", c.pivot_ratio},
      {"stiffness_penalized", nullptr},
      {"stiffness_free_dofs", nullptr}};
  if (c.stiffness_estimated) {
    j["stiffness_penalized"] = spectrum_json(c.penalized);
    j["stiffness_free_dofs"] = spectrum_json(c.free_dofs);
  }
  return j;
}

nlohmann::json timing_json(const PlateRunTimings& t, int cases_solved) {
  return {{"shape_functions_s", t.build.shape_functions_s},
          {"assembly_s", t.build.assembly_s},
          {"penalty_s", t.build.penalty_s},
          {"factorisation_s", t.build.factorisation_s},
          {"solves_s", t.solves_s},
          {"total_s", t.total_s},
          {"conditioning_s", t.conditioning_s},
          {"cases_solved", cases_solved},
          {"threads", thread_count()}};
}

nlohmann::json dataset_payload(const std::string& scene_key, const nlohmann::json& scene, const RpimSettings& settings,
                               const DatasetSpec& spec, const SceneRun& run, bool all_nodes) {
  nlohmann::json payload;
  payload["dataset"] = {{"kind", dataset_kind_name(spec.kind)},
                        {"count", static_cast<int>(run.forces.size())},
                        {"seed", spec.kind == DatasetKind::random ? nlohmann::json(spec.seed) : nlohmann::json(nullptr)}};
  if (spec.kind == DatasetKind::random)
    payload["dataset"]["generator"] =
        "mt19937_64(seed); u = (w >> 11) * 2^-53; |F| = max_force u1, cos(theta) = 2 u2 - 1, phi = 2 pi u3";
  payload["dataset"]["max_force"] = spec.max_force;
  payload[scene_key] = scene;
  payload[scene_key]["fixed_nodes"] = run.fixed_nodes;
  payload[scene_key]["mean_spacing"] = run.mean_spacing;
  payload["model"] = rpim_settings_json(settings, run.rbf, run.support, run.mean_spacing);
  payload["loaded_node"] = run.loaded_node_number;
  payload["loaded_node_index"] = run.loaded_node_index;
  nlohmann::json top = nlohmann::json::array();
  for (int n : run.top_nodes) top.push_back(vec3(run.nodes[n]));
  payload["top_nodes"] = top;
  nlohmann::json cases = nlohmann::json::array();
  for (std::size_t c = 0; c < run.forces.size(); ++c) {
    const Eigen::VectorXd u = run.displacements.col(static_cast<Eigen::Index>(c));
    nlohmann::json item = {{"force", vec3(run.forces[c])}, {"top_displacement", node_displacements(u, run.top_nodes)}};
    if (all_nodes) {
      nlohmann::json all = nlohmann::json::array();
      for (std::size_t i = 0; i < run.nodes.size(); ++i) all.push_back(vec3(u.segment<3>(3 * i)));
      item["displacement"] = all;
    }
    cases.push_back(item);
  }
  payload["cases"] = cases;
  nlohmann::json unit = nlohmann::json::array();
  for (int a = 0; a < 3; ++a) unit.push_back(node_displacements(run.unit_solutions.col(a), run.top_nodes));
  payload["unit_solutions"] = unit;
  if (all_nodes) {
    nlohmann::json nodes = nlohmann::json::array();
    for (const auto& x : run.nodes) nodes.push_back(vec3(x));
    payload["nodes"] = nodes;
  }
  payload["conditioning"] = conditioning_json(run.conditioning, settings.max_moment_condition);
  payload["timing"] = timing_json(run.timings, static_cast<int>(run.forces.size()) + 3);
  return payload;
}

nlohmann::json stability_point_json(const StabilityPoint& p, double max_moment_condition) {
  nlohmann::json j = {{"parameter", stability_parameter_name(p.parameter)},
                      {"value", p.value},
                      {"status", p.ok ? "ok" : "numerical_error"},
                      {"message", p.ok ? nlohmann::json(nullptr) : nlohmann::json(p.message)}};
  if (p.ok) {
    j["compliance"] = vec3(p.compliance);
    j["shape_length"] = p.rbf.shape_length();
    j["support"] = p.support.kind == SupportRule::Kind::radius
                       ? nlohmann::json{{"kind", "radius"}, {"radius", p.support.radius}}
                       : nlohmann::json{{"kind", "nearest"}, {"count", p.support.count}};
    j["conditioning"] = conditioning_json(p.conditioning, max_moment_condition);
  }
  return j;
}

}  // namespace softsim::meshless
