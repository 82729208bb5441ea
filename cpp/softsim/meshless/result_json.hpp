#pragma once
// JSON payloads of rpim_precompute's artifacts (schemas rpim_dataset, rpim_stability,
// rpim_convergence, all version 1; every quantity SI).
#include <string>

#include <nlohmann/json.hpp>

#include "softsim/meshless/load_cases.hpp"
#include "softsim/meshless/plate_dataset.hpp"
#include "softsim/meshless/studies.hpp"

namespace softsim::meshless {

nlohmann::json conditioning_json(const PlateConditioning& c, double max_moment_condition);
nlohmann::json timing_json(const PlateRunTimings& t, int cases_solved);

// The "rpim_dataset" payload; all_nodes adds "nodes" and each case's "displacement" of every node.
// `scene_key` names the scene's block ("plate" or "organ"), `scene` its echo.
nlohmann::json dataset_payload(const std::string& scene_key, const nlohmann::json& scene, const RpimSettings& settings,
                               const DatasetSpec& spec, const SceneRun& run, bool all_nodes);

nlohmann::json stability_point_json(const StabilityPoint& p, double max_moment_condition);

}  // namespace softsim::meshless
