#pragma once
// Linked asynchronous FEM regions (001 §5) on a tetrahedral dhd_sim model, one haptic frame at
// a time. The primary region (primary_region.hpp) is the dhd_sim engine itself on the primary
// elements (any element kinds, the same explicit central difference, 000 eq. 33, the same
// substeps per frame as the whole model); the secondary region is linear and quasi-static with
// its factorisation computed once (secondary_region.hpp), coupled by
//   exchange:   001 eq. 7: solved every `secondary_every` frames from the primary's interior
//               displacement; the interface nodes are prescribed in the primary region to the
//               values it publishes, held or interpolated between updates (001 Fig. 4);
//   condensed:  its stiffness condensed onto the interface, a force on the primary region at
//               every substep; its own nodes recovered every `secondary_every` frames (pictures);
//               optionally its mass too (Guyan), lumped onto the interface nodes, and a few
//               of its fixed-interface modes stepped with the primary region (Craig–Bampton).
// Skipping (issue: "skip what the scene does not need"): a secondary update whose input moved
// by less than `skip_below` since the last update is not done; the count is kept.
// Rigid tools (the model's boundary.tools) act on the primary region's interior nodes only: the
// caller keeps every node a tool may touch interior (RegionTracker::cover). A topology change
// (a cut) inside the primary region is the engine's local update; one that reaches the
// secondary region invalidates its factorisation, and the caller builds the region anew.
#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/regions/primary_region.hpp"
#include "softsim/regions/secondary_region.hpp"

namespace softsim::regions {

enum class Coupling { exchange, condensed };

// The primary region's size (001 §5 "adaptable asynchronous regions", Fig. 5): fixed, or a
// radius that grows with the deformation between a minimum and a maximum, in `levels` steps
// (each level's region is built once per contact node and kept).
struct AdaptiveRadius {
  enum class Kind {
    fixed,      // always RegionOptions::radius
    linear,     // 001 Fig. 5: r = radius + gradient × |u_contact|, clamped to [radius, max_radius]
    threshold,  // r = distance to the contact node of the farthest node (within max_radius) that
                // moved more than `threshold`: the region holds all of the visible deformation
  };
  Kind kind = Kind::fixed;
  double max_radius = 0.04;  // m
  double gradient = 2.0;     // m of radius per m of contact displacement
  double threshold = 1e-3;   // m
  int levels = 4;            // radii radius ... max_radius, evenly spaced
  int hold_frames = 100;     // a region shrinks only after the smaller size held this many frames
};

struct RegionOptions {
  double radius = 0.02;         // m: primary elements have a node this close to the contact node
  Coupling coupling = Coupling::condensed;
  int secondary_every = 10;     // frames between secondary updates (a rate of 1 kHz / every)
  bool interpolate = true;      // exchange: interface values interpolated between updates (001 Fig. 4)
  double skip_below = 0;        // m: skip a secondary update whose input moved less (0: never skip)
  // Exchange: the secondary region implicit-dynamic with the step secondary_every × frame step
  // (its inertia and damping; 001 §4's implicit solver) instead of quasi-static.
  bool secondary_dynamic = false;
  // Condensed: the far field's inertia in its static shape (Guyan), lumped onto the interface
  // nodes of the primary region (secondary_region.hpp) instead of a massless far field.
  bool far_field_mass = false;
  // Condensed with the Guyan mass: this many of the far field's lowest fixed-interface modes
  // kept and stepped with the primary region (Craig–Bampton; secondary_region.hpp). 0: Guyan.
  int far_field_modes = 0;
  // Condensed: the interface product in single precision (CondensedSecondary::use_single_precision).
  bool single_precision = false;
  AdaptiveRadius adaptive;
  // Where a new region (the contact moved on, a size change, a cut that reaches the far field)
  // is built: in the frame that needs it (inline), or on a worker thread beside the frames while
  // the current region keeps answering (background; RegionTracker). Background only: the frames
  // after the request at which the built region is swapped in, waiting for the worker if it is
  // not done (>= 0: the same frame whatever the machine, for reproducible offline runs), or -1:
  // at the first frame boundary after it is done (a live device never waits).
  bool build_in_background = false;
  int swap_after_frames = -1;
  // Background: a region around the contact node is requested before the contact leaves the
  // current one, once the contact node lies farther than this fraction of the radius from the
  // centre (the next region is usually ready when it is needed).
  double prefetch_fraction = 0.5;
};

struct RegionStats {
  long frames = 0;
  long secondary_updates = 0;   // secondary solves (exchange) or recoveries (condensed) done
  long secondary_skipped = 0;   // of those due, skipped because nothing near moved
  double setup_seconds = 0;     // building the primary engine and the secondary factorisation
  double secondary_seconds = 0; // secondary solves / recoveries, summed
  double secondary_max_seconds = 0;
  double secondary_setup_seconds = 0;  // of setup_seconds: the secondary's factorisation (and condensation)
  long local_cuts = 0;                 // cuts done by the primary engine's local update
  double local_cut_seconds = 0, local_cut_max_seconds = 0;
  double interface_seconds = 0; // condensed: the interface product (−S u_I) of every substep, summed
  // Condensed: far-field recoveries actually solved. A recovery falls due every secondary_every
  // frames but is solved only when something reads the far field before the next one is due (a
  // picture, a snapshot, a contact search that reaches it, a hand-over); secondary_updates counts
  // the due ones.
  long far_field_recoveries = 0;
};

class RegionSolver {
 public:
  // `model`: the scene's dhd_sim config (explicit, step `dt`), `kinds` its partition (one per
  // tetrahedron of `mesh`), `masses` the whole mesh's lumped masses, `linear` the small-strain
  // model of the same mesh. InputError for a scene the regions do not support (loads, a probe
  // spring in the config: the haptic loop is the only input). Elements `linear` marks removed
  // are in neither region (`region` is selected without them).
  RegionSolver(const mesh::TetMesh& mesh, const hybrid::DhdConfig& model, const std::vector<fem::ElementKind>& kinds,
               const std::vector<double>& masses, const LinearModel& linear, double dt, int substeps,
               PrimaryRegion region, const RegionOptions& options);

  // Starts from displacement `u` (3 per node, global; empty: rest) with the previous step's
  // displacement `u_before` (empty: at rest, u(−Δt) = u): the central difference resumes from
  // there (ExplicitSolver::set_resumed_state). A region moved to follow the contact starts from
  // the state its predecessor published.
  void start_from(const std::vector<double>& u, const std::vector<double>& u_before);
  // One haptic frame with `forces` (global nodes, interior to the primary region) acting.
  void frame(const std::vector<dynamics::AppliedForce>& forces);
  // One haptic frame with the probe's spring integrated at every substep instead of held over the
  // frame: k (anchor − x_c) on the contact triangle's nodes (global, interior; barycentric
  // `weights`), x_c from the current substep's displacement (HapticOptions::spring_coupling).
  void frame_with_spring(const std::array<int, 3>& nodes, const Eigen::Vector3d& weights, const Eigen::Vector3d& anchor,
                         double k);
  // Whether a node is solved every frame with forces allowed on it.
  bool interior(int node) const { return region_.interior[node] != 0; }
  // The whole mesh's displacement as the regions publish it (3 per node): the primary region's
  // now, the secondary region's from its last due update (condensed: solved here if it was
  // deferred, exactly what an eager recovery would have written; the forces never depend on it).
  const double* displacement() const;
  // The same array without solving a deferred recovery: current on the primary region's nodes
  // (interior and interface), possibly older on the far field's.
  const double* published() const { return u_.data(); }
  // Per global node: 1 where published() may be older than displacement() (not a primary node).
  const std::vector<char>& far_nodes() const { return far_nodes_; }
  // Brings the secondary region up to the primary's current state now (a region about to be
  // replaced publishes a current field for its successor).
  void refresh_secondary();
  // The primary region's displacement one step ago into `u` (global layout; other nodes
  // untouched).
  void primary_previous(double* u) const;
  // The whole published state one step ago into `u` (after refresh_secondary): the primary
  // region's previous step, and (condensed) the far field recovered at that step from the
  // interface's previous displacement and the modes' previous state, so a successor resumes the
  // far field's motion too.
  void previous_state(double* u);
  const PrimaryRegion& region() const { return region_; }

  // ---- rigid tools (the model's boundary.tools, on the primary interior's nodes) ----
  void set_tool_position(int k, const Eigen::Vector3d& centre) { solver_->set_tool_position(k, centre); }
  Eigen::Vector3d tool_force(int k) const { return solver_->tool_force(k); }
  int tool_contacts(int k) const { return solver_->tool_contacts(k); }

  // ---- topology changes (cuts) ----
  // Whether removing `elements` (global indices) changes the secondary region's system: a
  // secondary element, or (exchange, whose secondary rows include the interface) a primary
  // element on an interface node. Then the region must be built anew.
  bool secondary_affected(const std::vector<int>& elements) const;
  // The primary engine's local update (ExplicitSolver::remove_elements) for elements that do not
  // affect the secondary; the elements not in this region are ignored.
  void remove_primary_elements(const std::vector<int>& elements);
  const RegionStats& stats() const { return stats_; }

 private:
  void publish_primary();
  // The spring's force on its three nodes at the current substep into applied_[0..2].
  void spring_forces();
  void advance_frame(std::size_t contact_forces);
  // The published displacement of the interface nodes into `out` (3 per interface node).
  void published_interface(std::vector<double>& out) const;
  void secondary_update(bool forced = false);
  double gravity_factor() const;

  const mesh::TetMesh* mesh_;
  PrimaryRegion region_;
  RegionOptions options_;
  int substeps_ = 1;
  dynamics::Scene scene_;           // the primary region's scene (sub-mesh numbering)
  std::unique_ptr<fem::ElementSet> elements_;
  std::unique_ptr<dynamics::ExplicitSolver> solver_;
  std::unique_ptr<ExchangeSecondary> exchange_;
  std::unique_ptr<CondensedSecondary> condensed_;
  mutable std::vector<double> u_;  // global published displacement (a deferred recovery fills its far field)
  std::vector<char> far_nodes_;     // per global node: not a primary node
  // Exchange: the interface values of the last two secondary updates (3 per interface node) and
  // the frame of the last one.
  std::vector<double> interface_before_, interface_last_;
  long last_update_ = 0;
  // Condensed: the interface displacement and force buffers (3 per interface node).
  std::vector<double> interface_u_, interface_f_;
  std::vector<dynamics::AppliedForce> applied_;  // contact forces (local nodes) + interface forces
  std::vector<double> input_at_update_;          // what the last secondary update saw (skipping)
  // The spring of frame_with_spring during that frame: local nodes, weights, anchor, stiffness.
  bool spring_ = false;
  std::array<int, 3> spring_local_{};
  Eigen::Vector3d spring_weights_ = Eigen::Vector3d::Zero(), spring_anchor_ = Eigen::Vector3d::Zero();
  double spring_k_ = 0;
  mutable RegionStats stats_;  // a deferred recovery done on reading counts and times itself
  // Condensed: solves the deferred recovery, if one is kept, into u_.
  void recover_far_field() const;
};

}  // namespace softsim::regions
