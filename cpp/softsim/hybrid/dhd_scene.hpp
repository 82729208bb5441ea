#pragma once
// One dhd_sim scene, built from the same config dhd_sim reads, as an object a caller steps:
// set-up once (partition, critical step, element set, lumped masses, the explicit solver), then
//   scene.step(n); read displacement / velocity / reactions / probe force / energies in place;
//   move a prescribed displacement or the probe between steps; repeat.
// This is the loop researchers write around a simulation (move the tool, step, read the force)
// and the one engine under dhd_sim (run() is the whole configured run) and the Python API.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/cutting/blade.hpp"
#include "softsim/cutting/separation.hpp"
#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/dynamics/spectral_step.hpp"
#include "softsim/dynamics/stable_step.hpp"
#include "softsim/dynamics/static_solver.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::hybrid {

class DhdScene {
 public:
  // The partition is made from `config.partition`, or given as `kinds` (one per tetrahedron).
  // Throws InputError (bad step request, bad scene) as dhd_sim would report it.
  DhdScene(std::shared_ptr<const mesh::TetMesh> mesh, DhdConfig config);
  DhdScene(std::shared_ptr<const mesh::TetMesh> mesh, DhdConfig config, std::vector<fem::ElementKind> kinds);
  DhdScene(const DhdScene&) = delete;
  DhdScene& operator=(const DhdScene&) = delete;

  // The scene's mesh: with separating cuts a copy the cuts change (node copies appended).
  const mesh::TetMesh& mesh() const { return *mesh_; }
  std::shared_ptr<const mesh::TetMesh> mesh_ptr() const { return mesh_; }
  const DhdConfig& config() const { return config_; }
  const std::vector<fem::ElementKind>& kinds() const { return kinds_; }
  // 000 eq. 34's Δt_cr on the smallest altitude, always; with solver.critical_step
  // "power_iteration" also 2/ω_max of the lumped system at rest, which then sets the step.
  const dynamics::CriticalStep& critical_step() const { return critical_; }
  const std::optional<dynamics::SpectralStep>& spectral_step() const { return spectral_; }
  const dynamics::StepChoice& step_choice() const { return step_; }
  double setup_seconds() const { return setup_seconds_; }
  bool is_static() const { return config_.static_solver; }

  // ---- explicit dynamics (InputError if the config's solver is static) ----
  dynamics::ExplicitSolver& solver();
  const dynamics::ExplicitSolver& solver() const;
  void step(int n = 1) { solver().advance(n); }
  void reset() { solver().reset(); }
  double time() const { return solver().time(); }
  int steps_done() const { return solver().steps_done(); }
  double dt() const { return solver().dt(); }  // the step in use (it shrinks if re-estimated)
  int num_nodes() const { return mesh_->num_nodes(); }
  // u(t), 3 per node, in place: valid until the next step() or reset().
  const double* displacement() const { return solver().displacement(); }
  void velocity(double* out) const { solver().velocity(out); }
  std::vector<Eigen::Vector3d> reactions() { return solver().reactions(); }
  Eigen::Vector3d probe_force() const { return solver().probe_force(); }
  const std::vector<dynamics::EnergySample>& energies() const { return solver().energies(); }

  // Index of the constraint named `name` (boundary.fixed / boundary.prescribed entries, named as
  // in the dhd_result's "reactions"); InputError naming the known names if there is none.
  int constraint_index(const std::string& name) const;
  void set_prescribed_displacement(int constraint, const Eigen::Vector3d& value) {
    solver().set_prescribed_displacement(constraint, value);
  }
  // The probe's tip at world position `x` (m), from the next step on.
  void set_probe_position(const Eigen::Vector3d& x);
  // The probe tip's world position now.
  Eigen::Vector3d probe_position() const;

  // The whole configured run (config.explicit_solver.steps steps from t = 0), as dhd_sim runs it.
  dynamics::ExplicitResult run(const dynamics::SnapshotFn& snapshot = {}, const dynamics::ProgressFn& progress = {});

  // ---- cutting: element removal, or separation along faces ----
  struct CutEvent {
    double time = 0;
    int step = 0;
    CutMode mode = CutMode::remove;
    dynamics::CutReport report;  // what left, and the engine's local update time (removal)
    // Separation: the faces that opened, each split as (node, copy), the nodes of cut faces a
    // constraint holds (not split), and the time of the mesh and engine updates.
    int faces = 0;
    std::vector<std::array<int, 2>> copies;
    std::vector<int> moved_elements;  // the elements re-pointed to copies, ascending
    int held_nodes_kept = 0;
    double separation_seconds = 0;
    cutting::BoundaryChange boundary;  // what it did to the mesh's boundary triangles
    // With the step from power iteration: 2/ω_max of the cut system, measured again (s), and
    // the time that took (recheck_spectral_step); 0 otherwise.
    double stable_step = 0;
    double step_check_seconds = 0;
    int pieces = 0;              // connected pieces left after the cut
    int loose_pieces = 0;        // of them, held by no constraint
    double search_seconds = 0;   // finding the crossed elements
    double pieces_seconds = 0;   // finding the pieces
  };
  // Between steps: the elements the sweep crosses in the current geometry are removed
  // (ExplicitSolver::remove_elements). The config's "cuts" call it at their times. A sweep
  // that removes something is kept in cut_events(); the returned event also says what an empty
  // one cost (its search).
  // With CutMode::separate the mesh opens along the faces nearest the sweep instead
  // (cutting/separation.hpp; the config must allow it: DhdConfig::separates).
  // `u` (3 per node): the geometry to cut in when the model is not the one stepped (the linked
  // regions publish it); null: the model's own.
  CutEvent cut(const cutting::BladeSweep& sweep, CutMode mode = CutMode::remove, const double* u = nullptr);
  const std::vector<CutEvent>& cut_events() const { return cut_events_; }
  // Builds the structures the first cut would (the blade's element grid, and the face topology
  // when the scene separates), so that a cut's time is its own; returns the seconds taken.
  double prepare_cuts();
  bool removed(int element) const { return elements_ && elements_->removed(element); }

  // ---- static equilibrium of the same model (000 eq. 24) ----
  dynamics::StaticResult solve_static() const;

 private:
  std::shared_ptr<const mesh::TetMesh> mesh_;
  mesh::TetMesh* cut_mesh_ = nullptr;  // mesh_ itself when the scene separates (a copy it owns)
  DhdConfig config_;
  std::vector<fem::ElementKind> kinds_;
  dynamics::CriticalStep critical_;
  std::optional<dynamics::SpectralStep> spectral_;
  dynamics::StepChoice step_;
  std::unique_ptr<dynamics::DeformedCriticalStep> deformed_step_;
  std::unique_ptr<fem::ElementSet> elements_;
  std::vector<CutEvent> cut_events_;
  std::vector<char> held_;  // per node: some constraint holds it (for loose pieces)
  std::unique_ptr<cutting::ElementGrid> cut_grid_;  // built at the first cut: the blade's local search
  std::vector<int> cut_candidates_;
  std::unique_ptr<cutting::FaceTopology> topology_;  // built at the first separating cut
  CutEvent separate(const cutting::BladeSweep& sweep, CutEvent ev, const std::vector<int>& crossed, const double* u);
  void recheck_spectral_step(CutEvent& ev);
  double spectral_scale_ = 1.0;  // 2/ω_max over the altitude estimate, at rest (the deformed estimate's factor)
  std::unique_ptr<dynamics::ExplicitSolver> solver_;
  double setup_seconds_ = 0;
};

// The solver options of a dhd_sim config at time step `dt`.
dynamics::ExplicitOptions explicit_options(const DhdConfig& config, double dt);

}  // namespace softsim::hybrid
