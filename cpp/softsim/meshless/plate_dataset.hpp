#pragma once
// One precompute run on the plate of 002 §4.1: build and factor the RPIM model, solve every
// force of a dataset and the three unit forces at the loaded node, and collect the
// conditioning and timing figures that go with it.
#include <vector>

#include <Eigen/Core>

#include "softsim/meshless/conditioning.hpp"
#include "softsim/meshless/load_cases.hpp"
#include "softsim/meshless/plate_scene.hpp"
#include "softsim/meshless/rpim_model.hpp"

namespace softsim::meshless {

MeshlessProblem plate_problem(const PlateScene& scene);

struct PlateRunTimings {
  BuildTimings build;
  double solves_s = 0;        // all dataset cases + the 3 unit cases
  double conditioning_s = 0;  // diagnostics, not part of the precompute
  double total_s = 0;         // build + solves
};

struct PlateConditioning {
  ShapeTableStats moment;              // moment matrices at the Gauss points
  bool stiffness_estimated = false;
  SpectrumEstimate penalized;          // K with penalty terms (what is factored)
  SpectrumEstimate free_dofs;          // K restricted to unconstrained dofs
  RigidModeEnergy rigid_modes;         // K before boundary conditions
  double pivot_ratio = 0;              // smallest pivot / largest diagonal of K (no penalty)
};

struct PlateRun {
  std::vector<Eigen::Vector3d> nodes;
  std::vector<int> top_nodes;      // paper order
  std::vector<int> fixed_nodes;
  int loaded_node_index = 0;
  int loaded_node_number = 0;      // paper numbering (61)
  std::vector<Eigen::Vector3d> forces;
  Eigen::MatrixXd displacements;   // 3N × cases
  Eigen::MatrixXd unit_solutions;  // 3N × 3 (unit forces e_x, e_y, e_z, no body force)
  double mean_spacing = 0;
  RbfParams rbf;                   // resolved (d_c in metres)
  SupportRule support;             // resolved (radius in metres)
  PlateConditioning conditioning;
  PlateRunTimings timings;
};

// Throws NumericalError from the model; `stiffness_conditioning` adds the eigenvalue estimates.
PlateRun run_plate(const PlateScene& scene, const RpimSettings& settings, const std::vector<Eigen::Vector3d>& forces,
                   bool stiffness_conditioning);
// Several force sets on one model: built, factored and diagnosed once, each set then solved as
// the single-set run_plate solves it (same bits). Every run carries the shared build timings;
// its total_s is the build plus its own solves.
std::vector<PlateRun> run_plate_sets(const PlateScene& scene, const RpimSettings& settings,
                                const std::vector<std::vector<Eigen::Vector3d>>& force_sets,
                                bool stiffness_conditioning);

}  // namespace softsim::meshless
