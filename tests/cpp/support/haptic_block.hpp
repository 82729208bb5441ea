#pragma once
// The haptic tests' scene: an 8 x 8 x 4-cell block, 10 x 10 x 5 cm, bottom fixed, E = 5 kPa
// (000 §3.1), damped; a tool tip pressed straight down and held; a spring probe, with or without
// the linked regions; a vertical blade on the tool and its path across the block.
#include <algorithm>
#include <array>
#include <memory>
#include <set>

#include <nlohmann/json.hpp>

#include "softsim/cutting/blade.hpp"
#include "softsim/haptic/haptic_scene.hpp"
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

// A spring probe of `stiffness` (N/m); with `regions_radius` > 0 the linked regions with that
// primary radius instead of the whole model.
inline haptic::HapticOptions spring_probe(double stiffness = 100, double regions_radius = 0) {
  haptic::HapticOptions opt;
  opt.probe_stiffness = stiffness;
  if (regions_radius > 0) {
    opt.use_regions = true;
    opt.regions.radius = regions_radius;
  }
  return opt;
}

// A pushing spring probe (100 N/m) carrying a vertical blade 4 cm long, cutting in `mode`.
inline haptic::HapticOptions vertical_blade(hybrid::CutMode mode, double regions_radius = 0) {
  haptic::HapticOptions opt = spring_probe(100, regions_radius);
  opt.contact = haptic::ContactMode::push;
  opt.blade = true;
  opt.blade_edge = Eigen::Vector3d(0, 0, 0.04);
  opt.blade_mode = mode;
  return opt;
}

// The blade's path across the block: the tip 1 cm below the top, drawn along x from 3 to 7 cm at
// y = 5.2 cm over 401 frames.
inline void draw_blade_across(haptic::HapticScene& scene) {
  for (long k = 0; k <= 400; ++k) scene.frame(Eigen::Vector3d(0.03 + 0.04 * k / 400.0, 0.052, 0.04));
}

// A vertical blade drawn along x at y = y0 from x0 to x1, its edge between heights z0 and z1.
inline cutting::BladeSweep sweep_along_x(double x0, double x1, double y0, double z0, double z1) {
  cutting::BladeSweep s;
  s.a0 = {x0, y0, z0};
  s.b0 = {x0, y0, z1};
  s.a1 = {x1, y0, z0};
  s.b1 = {x1, y0, z1};
  return s;
}

// Oriented triangles as a set, each rotated to start at its smallest node (so two lists of the
// same oriented triangles compare equal whatever their order and starting corner).
template <class Triangles>
std::set<std::array<int, 3>> oriented_triangle_set(const Triangles& triangles) {
  std::set<std::array<int, 3>> out;
  for (std::array<int, 3> t : triangles) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.insert(t);
  }
  return out;
}

// The live triangles of a contact surface, as oriented_triangle_set.
inline std::set<std::array<int, 3>> surface_triangle_set(const haptic::ContactSurface& surface) {
  std::vector<std::array<int, 3>> live;
  for (int t = 0; t < surface.num_triangles(); ++t)
    if (surface.live(t)) live.push_back(surface.triangle(t));
  return oriented_triangle_set(live);
}

}  // namespace softsim::test_scenes
