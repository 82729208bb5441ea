#pragma once
// One precompute run on the plate of 002 §4.1 (scene_run.hpp with the plate's nodes, cells,
// supports and loaded node 61).
#include <vector>

#include <Eigen/Core>

#include "softsim/meshless/plate_scene.hpp"
#include "softsim/meshless/scene_run.hpp"

namespace softsim::meshless {

using PlateRunTimings = SceneRunTimings;
using PlateConditioning = SceneConditioning;
using PlateRun = SceneRun;

MeshlessProblem plate_problem(const PlateScene& scene);
SceneLayout plate_layout(const PlateScene& scene);

// Throws NumericalError from the model; `stiffness_conditioning` adds the eigenvalue estimates.
PlateRun run_plate(const PlateScene& scene, const RpimSettings& settings, const std::vector<Eigen::Vector3d>& forces,
                   bool stiffness_conditioning);
std::vector<PlateRun> run_plate_sets(const PlateScene& scene, const RpimSettings& settings,
                                     const std::vector<std::vector<Eigen::Vector3d>>& force_sets,
                                     bool stiffness_conditioning);

}  // namespace softsim::meshless
