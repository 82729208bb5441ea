#pragma once
// marquardt_fit's play mode (cpp/apps/marquardt_fit.md): a fitted model played back at a list of
// forces, optionally against a reference dataset's exact superposition -> "surface_playback"
// payload. Shared by the executable and the Python API, so that one config gives one payload.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "softsim/fit/dataset.hpp"
#include "softsim/fit/dataset_json.hpp"
#include "softsim/fit/model.hpp"
#include "softsim/io/json_reader.hpp"

namespace softsim::fit {

inline constexpr const char* kPlaybackSchema = "surface_playback";
inline constexpr int kPlaybackSchemaVersion = 1;

struct PlaybackConfig {
  std::string fit_path;                  // the marquardt_fit artifact
  std::vector<Eigen::Vector3d> forces;   // N
  DatasetRef reference;                  // a dataset with unit solutions, or an empty path
};

// Reads the whole play config (rejecting unknown keys) without touching any file.
PlaybackConfig read_playback_config(const io::JsonReader& config);

// InputError unless `dataset` lies on the model's surface nodes with the same loaded node.
void require_same_nodes(const Dataset& dataset, const FitModel& model);

// Reads the fitted model and the reference the config names and plays the forces back: each
// force's surface displacement, the loaded node's and relation 1's; with a reference, its exact
// superposition and the errors against it.
nlohmann::json play_back(const PlaybackConfig& config);

}  // namespace softsim::fit
