#pragma once
// The configuration of one asynchronous-regions run (the async_sim tool; reference in
// cpp/apps/async_sim.md) read strictly from JSON, and the artifact payload it produces.
#include <string>

#include <nlohmann/json.hpp>

#include "softsim/io/json_reader.hpp"
#include "softsim/multirate/bar_model.hpp"
#include "softsim/multirate/comparison.hpp"
#include "softsim/multirate/setup_error.hpp"

namespace softsim::multirate {

inline constexpr const char* kAsyncRunSchema = "async_run";
inline constexpr int kAsyncRunSchemaVersion = 1;

struct DampingSpec {
  bool by_ratio = true;  // true: alpha = 2 ratio omega_1 (lowest mode); false: alpha given
  double value = 0.5;
};

struct RunConfig {
  BarSpec bar;
  DampingSpec damping;
  ComparisonSpec comparison;
  int series_every = 0;  // keep every k-th frame of the signals in the artifact (0: none)
};

// Reads every key it knows and rejects the rest; errors name the file and JSON pointer.
// Checks what can be checked before building the model (ranges, choices, layout sizes).
RunConfig read_run_config(const io::JsonReader& config);

// What the model is, for the artifact and for the explicit-step check.
struct ModelSummary {
  int free_nodes = 0;
  double element_length = 0.0;           // m (bar)
  double lowest_frequency = 0.0;         // Hz
  double alpha = 0.0;                    // 1/s, c = alpha m
  double omega_max_bound = 0.0;          // rad/s
  double eq4_limit = 0.0;                // s, 001 eq. 4: L_e sqrt(rho / E)
  double explicit_limit_central = 0.0;   // s, eq. 5 on the whole model
  double explicit_limit_backward = 0.0;  // s, eq. 6 on the whole model
  double contact_static_stiffness = 0.0; // N/m, 1 / (K^-1)_cc
};

// Builds the reduced system (damping set) and fills the summary.
ReducedSystem build_system(const RunConfig& config, ModelSummary& summary);

// The config member (JSON pointer) that chose a setting found at fault in set-up.
std::string config_pointer(const SettingAtFault& setting);

// run_comparison on the configured run, with a setting at fault reported at its config member
// (ConfigInputError), like the errors of read_run_config.
ComparisonResult run_configured_comparison(const ReducedSystem& system, const RunConfig& config);

nlohmann::json make_payload(const RunConfig& config, const ModelSummary& model, const ComparisonResult& result);

}  // namespace softsim::multirate
