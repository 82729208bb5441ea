#pragma once
// Strict reading of the rpim_precompute configuration blocks (every key documented in
// cpp/apps/rpim_precompute.md) and their echo, with every default resolved, into artifacts.
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "softsim/io/json_reader.hpp"
#include "softsim/meshless/load_cases.hpp"
#include "softsim/meshless/manufactured.hpp"
#include "softsim/meshless/plate_scene.hpp"
#include "softsim/meshless/rpim_model.hpp"

namespace softsim::meshless {

// Each reader consumes its block (absent block: all defaults) and rejects unknown keys. A key
// left out keeps the struct's default (its member initialisers, the one place defaults are set).
PlateScene read_plate_scene(const std::optional<io::JsonReader>& block);
RpimSettings read_rpim_settings(const std::optional<io::JsonReader>& rpim,
                                const std::optional<io::JsonReader>& penalty,
                                const std::optional<io::JsonReader>& solver);
DatasetSpec read_dataset_spec(const io::JsonReader& block);

// Mode dataset's "output" block.
struct DatasetOutput {
  bool all_nodes = false;               // every node's position and displacement too
  bool stiffness_conditioning = false;  // the Lanczos estimate of cond(K), only when asked
};
DatasetOutput read_dataset_output(const std::optional<io::JsonReader>& block);
BlockStudy read_block_study(const std::optional<io::JsonReader>& block);

// Lee–Radok inputs of 002 §4.1 (SI), optional in a config.
struct IndentationInputs {
  double force = 0, depth = 0, probe_radius = 0, poisson_ratio = 0;
};
IndentationInputs read_indentation(const io::JsonReader& block);

nlohmann::json plate_scene_json(const PlateScene& s);
// The settings as resolved for a run: d_c and the support radius in metres.
nlohmann::json rpim_settings_json(const RpimSettings& s, const RbfParams& resolved_rbf,
                                  const SupportRule& resolved_support, double mean_spacing);

}  // namespace softsim::meshless
