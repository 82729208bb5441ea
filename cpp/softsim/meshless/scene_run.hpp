#pragma once
// One precompute run on any RPIM scene (the plate of 002 §4.1, an organ of §5.3): build and
// factor the model, solve every force of a dataset at the loaded node and the three unit forces
// there, and collect the conditioning and timing figures that go with it.
#include <vector>

#include <Eigen/Core>

#include "softsim/meshless/conditioning.hpp"
#include "softsim/meshless/rpim_model.hpp"

namespace softsim::meshless {

// Which nodes a scene reports, holds and loads.
struct SceneLayout {
  std::vector<int> reported_nodes;  // the surface a dataset stores (plate: top layer in paper order)
  std::vector<int> fixed_nodes;     // held by penalty supports (already in the problem's constraints)
  int loaded_node_index = 0;        // among all nodes
  int loaded_node_number = 0;       // 1-based position among reported_nodes (the plate's 61)
  Eigen::Vector3d body_force = Eigen::Vector3d::Zero();  // N/m³, added to every dataset case
};

struct SceneRunTimings {
  BuildTimings build;
  double solves_s = 0;        // all dataset cases + the 3 unit cases
  double conditioning_s = 0;  // diagnostics, not part of the precompute
  double total_s = 0;         // build + solves
};

struct SceneConditioning {
  ShapeTableStats moment;              // moment matrices at the Gauss points
  bool stiffness_estimated = false;
  SpectrumEstimate penalized;          // K with penalty terms (what is factored)
  SpectrumEstimate free_dofs;          // K restricted to unconstrained dofs
  RigidModeEnergy rigid_modes;         // K before boundary conditions
  double pivot_ratio = 0;              // smallest pivot / largest diagonal of K (no penalty)
};

struct SceneRun {
  std::vector<Eigen::Vector3d> nodes;
  std::vector<int> top_nodes;      // the reported surface (plate: paper order)
  std::vector<int> fixed_nodes;
  int loaded_node_index = 0;
  int loaded_node_number = 0;      // 1-based among top_nodes (the plate's 61)
  std::vector<Eigen::Vector3d> forces;
  Eigen::MatrixXd displacements;   // 3N × cases
  Eigen::MatrixXd unit_solutions;  // 3N × 3 (unit forces e_x, e_y, e_z, no body force)
  double mean_spacing = 0;
  RbfParams rbf;                   // resolved (d_c in metres)
  SupportRule support;             // resolved (radius in metres)
  SceneConditioning conditioning;
  SceneRunTimings timings;
};

// Several force sets on one model: built, factored and diagnosed once, each set then solved as a
// run of that set alone would solve it (same bits). Every run carries the shared build timings;
// its total_s is the build plus its own solves. Throws NumericalError from the model;
// `stiffness_conditioning` adds the eigenvalue estimates.
std::vector<SceneRun> run_scene_sets(const MeshlessProblem& problem, const SceneLayout& layout,
                                     const RpimSettings& settings,
                                     const std::vector<std::vector<Eigen::Vector3d>>& force_sets,
                                     bool stiffness_conditioning);

}  // namespace softsim::meshless
