#pragma once
// The three runs of rpim_precompute (cpp/apps/rpim_precompute.md), each from its whole config:
//   dataset      solve a force set at the loaded node          -> "rpim_dataset" payload
//   stability    vary one RPIM parameter at a time             -> "rpim_stability" payload
//   convergence  refine a block with a manufactured solution   -> "rpim_convergence" payload
// Shared by the executable and the Python API, so that one config gives one payload.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "softsim/io/json_reader.hpp"

namespace softsim::meshless {

inline constexpr int kRpimSchemaVersion = 1;

struct RpimOutput {
  std::string schema;                  // artifact schema name, version kRpimSchemaVersion
  nlohmann::json payload;
  std::optional<std::uint64_t> seed;   // the random dataset's seed, for the provenance
  std::string summary;                 // one line for the log
};

// The mode names, the default first.
inline const std::vector<std::string> kRpimModes = {"dataset", "stability", "convergence"};

// Reads the whole config (rejecting unknown keys before computing), then runs. InputError for
// bad input, NumericalError for a failed model (the stability sweep records its failures instead).
RpimOutput run_rpim_mode(const std::string& mode, const io::JsonReader& config);

}  // namespace softsim::meshless
