#pragma once
// The haptic tests' scene: an 8 x 8 x 4-cell block, 10 x 10 x 5 cm, bottom fixed, E = 5 kPa
// (000 §3.1), damped; and a tool tip pressed straight down and held.
#include <memory>

#include <nlohmann/json.hpp>

#include "softsim/haptic/probe_path.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/io/json_reader.hpp"
#include "support/scenes.hpp"

namespace softsim::test_scenes {

struct HapticBlock {
  std::shared_ptr<const mesh::TetMesh> mesh = std::make_shared<const mesh::TetMesh>(cuboid(8, 8, 4, 0.1, 0.1, 0.05));
  static nlohmann::json paper_material() { return {{"E", 5000.0}, {"nu", 0.35}, {"density", 1000.0}}; }
  hybrid::DhdConfig config(double damping, const nlohmann::json& material = paper_material()) const {
    const nlohmann::json j = {{"mesh", "unused"},
                              {"material", material},
                              {"damping", {{"alpha", damping}}},
                              {"boundary", {{"fixed", {{{"set", "bottom"}}}}}},
                              {"solver", {{"kind", "explicit"}}}};
    return hybrid::read_dhd_config(io::JsonReader(j, "block.json"), *mesh);
  }
  // The paper's (E, ν, ρ) with material.model `model`.
  hybrid::DhdConfig config(double damping, const char* model) const {
    nlohmann::json material = paper_material();
    material["model"] = model;
    return config(damping, material);
  }
};

// Pressed straight down (−z, ProbePath's default) from `origin` to `depth` over `ramp_time`, held.
inline haptic::ProbePath press_down(const Eigen::Vector3d& origin, double depth, double ramp_time) {
  haptic::ProbePath path;
  path.origin = origin;
  path.signal.kind = multirate::ProbeSignal::Kind::kRampHold;
  path.signal.amplitude = depth;
  path.signal.ramp_time = ramp_time;
  return path;
}

}  // namespace softsim::test_scenes
