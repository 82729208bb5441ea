#pragma once
// The cutting tests' pressed block: the 4 cm cuboid, bottom fixed, top pushed down 4 mm over
// 0.05 s, damped (α = 5), cut at t = 0.06 s by a blade across the top at x = 2.1 cm, pushed from
// above it down to 2 cm; `mode` empty for the config's default (removal).
#include <string>

#include <nlohmann/json.hpp>

namespace softsim::test_scenes {

inline nlohmann::json pressed_block_cut(const std::string& mode = "", int steps = 20000) {
  nlohmann::json j = nlohmann::json::parse(R"({
    "mesh": "m",
    "material": {"model": "neo_hookean_decoupled", "E": 5000, "nu": 0.35, "density": 1000},
    "damping": {"alpha": 5},
    "boundary": {"fixed": ["bottom"], "prescribed": [{"set": "top", "displacement": [0, 0, -0.004], "ramp_time": 0.05}]},
    "solver": {"kind": "explicit", "energy_interval": 500},
    "cuts": [{"time": 0.06, "from": [[0.021, -0.01, 0.05], [0.021, 0.05, 0.05]], "to": [[0.021, -0.01, 0.02], [0.021, 0.05, 0.02]]}]
  })");
  j["solver"]["steps"] = steps;
  if (!mode.empty()) j["cuts"][0]["mode"] = mode;
  return j;
}

}  // namespace softsim::test_scenes
