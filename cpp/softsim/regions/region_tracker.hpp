#pragma once
// The linked regions of a live scene (001 §5): which primary region is active, and the hand-over
// between regions. The active region's interior holds the contact triangle; it is centred on the
// contact's nearest node and sized by the policy (AdaptiveRadius) from the current deformation.
// When the contact slides out of the interior or the size changes, the next region takes over
// the state the current one publishes (its secondary brought up to date first, the central
// difference resumed) so the force does not jump. Regions built for the current contact node are
// kept, so a size that comes back is not built again (001 precomputes one system per size).
// With a rigid tool the region is placed by the nodes the tool touches or may touch (cover):
// all of them interior, the region grown past the adaptive sizes when the contact set needs it.
// A topology change (topology_changed) is a local update of the active primary engine where
// it can be, else the active region is built anew on the cut mesh, and cached regions the
// change reaches are dropped.
#include <array>
#include <future>
#include <map>
#include <memory>
#include <vector>

#include "softsim/multirate/region_layout.hpp"
#include "softsim/regions/region_solver.hpp"
#include "softsim/regions/topology_change.hpp"

namespace softsim::regions {

struct RegionBuilds {
  long builds = 0;        // regions built
  long switches = 0;      // hand-overs between regions (moves and size changes)
  double seconds = 0, max_seconds = 0;  // building them
  long tool_covers = 0;    // hand-overs the tool's contact set asked for (moved or grown)
  long late_contacts = 0;  // nodes found in the tool after a frame outside the primary interior
  // Background builds (RegionOptions::build_in_background): regions built on the worker, those
  // swapped in, what a swap cost on the frame thread (the state carried over: the far field
  // recovered, the successor started), the frames answered while a build ran, and how long the
  // frame thread waited for the worker (swap_after_frames >= 0 only).
  long background_builds = 0;
  long swaps = 0;
  double swap_seconds = 0, swap_max_seconds = 0;
  long frames_while_building = 0;
  double wait_seconds = 0, wait_max_seconds = 0;
  long discarded = 0;  // built on a mesh a later cut changed: thrown away, built again
};

class RegionTracker {
 public:
  // InputError for bad options (a maximum radius below the radius, fewer than 2 levels, ...).
  RegionTracker(const mesh::TetMesh& mesh, const hybrid::DhdConfig& model, std::vector<fem::ElementKind> kinds,
                double dt, int substeps, const RegionOptions& options);
  ~RegionTracker();  // waits for a build in flight
  RegionTracker(const RegionTracker&) = delete;
  RegionTracker& operator=(const RegionTracker&) = delete;

  // Background builds: at a frame's start, before anything reads the regions: a finished build
  // is swapped in (its predecessor's state carried over), or waited for when it is due
  // (swap_after_frames >= 0). Nothing otherwise.
  void between_frames(long frame);
  // Waits for a build in flight and swaps it in (before a cut that changes the mesh itself, a
  // separation, which the worker must not read while it changes).
  void finish_building();
  // Whether a region is being built on the worker now.
  bool building() const { return pending_.valid(); }

  // Makes the active region one that suits the contact on `nodes` with `weights` (barycentric):
  // centred on the node of largest weight, whose neighbours are always interior.
  void follow(const std::array<int, 3>& nodes, const Eigen::Vector3d& weights, long frame);
  // A rigid tool: makes the active region one whose interior holds every node in `nodes` (the
  // nodes the tool touches or may touch, tool_cover.hpp), re-centred on them when the current
  // one does not, and grown beyond the adaptive sizes (in the same radius steps) when they
  // spread wider; the adaptive policy still applies around the centre. Nothing for no nodes.
  void cover(const std::vector<int>& nodes, long frame);
  // After a frame: how many of `touched` (nodes the tool touches now) are outside the primary
  // interior (their contact was not computed this frame); counted as late contacts. The next
  // cover() takes them in.
  int count_late_contacts(const std::vector<int>& touched);
  // One frame of the active region (none yet: nothing moves).
  void frame(const std::vector<dynamics::AppliedForce>& forces);
  // One frame with the probe's spring integrated at every substep (RegionSolver::frame_with_spring).
  void frame_with_spring(const std::array<int, 3>& nodes, const Eigen::Vector3d& weights, const Eigen::Vector3d& anchor,
                         double k);
  // One frame with rigid tool k at `centre` (none active yet: nothing moves, no force).
  void frame_with_tool(int k, const Eigen::Vector3d& centre);
  Eigen::Vector3d tool_force(int k) const { return active_ ? active_->tool_force(k) : Eigen::Vector3d::Zero(); }
  int tool_contacts(int k) const { return active_ ? active_->tool_contacts(k) : 0; }
  // Elements removed or changed by a cut (topology_change.hpp).
  void topology_changed(const TopologyChange& change);
  const TopologyStats& topology_stats() const { return topology_; }
  // Per element: removed by a cut so far.
  const std::vector<char>& removed() const { return removed_; }
  // Every region back to rest (recovery from a numerical failure).
  void back_to_rest();
  // The published displacement with the far field current (a deferred recovery solved now if
  // one is due: RegionSolver::displacement()); published(): without solving it, current on the
  // active primary region's nodes only; far_nodes(): where published() may be older (null: none).
  const double* displacement() const { return active_ ? active_->displacement() : rest_.data(); }
  const double* published() const { return active_ ? active_->published() : rest_.data(); }
  const std::vector<char>* far_nodes() const { return active_ ? &active_->far_nodes() : nullptr; }
  const RegionSolver* active() const { return active_; }
  double active_radius() const { return active_ ? active_->region().radius : 0.0; }
  const RegionBuilds& builds() const { return builds_; }
  // Statistics summed over every region used, for the frames each was active.
  RegionStats totals() const;
  // Frames spent at each size level (index: level).
  const std::vector<long>& frames_per_level() const { return level_frames_; }

 private:
  struct Built {
    std::unique_ptr<RegionSolver> solver;
    std::shared_ptr<LinearModel> linear;
  };
  struct Finished {
    int centre = -1, level = -1;
    long generation = 0;
    bool for_cut = false;
    std::unique_ptr<RegionSolver> solver;
    std::shared_ptr<LinearModel> linear;
    std::vector<double> masses;  // with linear: the cut mesh's lumped masses
    double seconds = 0;          // the build on the worker, linear model included
    double secondary_seconds = 0;
  };
  int target_level(int centre, long frame);
  double level_radius(int level) const;
  // The smallest level whose region around `centre` holds `nodes` as near nodes.
  int covering_level(int centre, const std::vector<int>& nodes) const;
  void set_centre(int centre);
  void activate(int centre, int level);
  // A region built now at (centre, level) on the current cut mesh; its build time into `seconds`.
  std::unique_ptr<RegionSolver> build(int centre, int level, double& seconds);
  // The small-strain model and the lumped masses of the mesh a cut left (after a cut, at the
  // next build), the old model kept while regions built on it remain.
  void update_linear();
  // ---- background builds ----
  // Asks the worker for the region (centre, level) on the current cut mesh; nothing if a build
  // is in flight already (the next frames ask again once it is done).
  void request(int centre, int level, long frame, bool for_cut);
  // Takes the worker's region now (waiting for it if it is not done) and swaps it in.
  void take_finished();
  // The worker's region made active, starting from the state the active one publishes.
  void swap_in(Finished&& done);
  // The state the active region publishes, brought up to date (what a successor starts from).
  // `n3`: its length (0: the current mesh's 3 × nodes; before a separation's copies, the old).
  void published_state(std::vector<double>& u, std::vector<double>& u_before, std::size_t n3 = 0);

  const mesh::TetMesh* mesh_;
  hybrid::DhdConfig model_;
  std::vector<fem::ElementKind> kinds_;
  double dt_;
  int substeps_;
  RegionOptions options_;
  std::vector<double> masses_;
  std::shared_ptr<LinearModel> linear_;
  bool linear_stale_ = false;  // a cut since linear_ and masses_ were made
  std::vector<char> removed_;  // per element
  std::vector<double> rest_;
  // Regions built around the current contact node, by size level, each with the linear model it
  // was built on.
  int centre_ = -1;
  std::map<int, Built> built_;
  int near_centre_ = -1;  // the centre near_nodes_ were found around
  // The build in flight on the worker (background), what it was asked for, and the topology
  // generation (cuts told so far) it was built on; active_stale_: a cut reached the active
  // region's far field and its successor on the cut mesh is still to come.
  std::future<Finished> pending_;
  int pending_centre_ = -1, pending_level_ = -1;
  long pending_frame_ = 0;
  long generation_ = 0;
  bool active_stale_ = false;
  int contact_node_ = -1;  // the contact's node of largest weight at the last follow()
  RegionSolver* active_ = nullptr;
  int active_level_ = -1;
  RegionStats active_from_;  // the active region's statistics when it became active
  RegionStats retired_;      // summed over the regions' earlier active spells
  RegionBuilds builds_;
  TopologyStats topology_;
  multirate::SlidingMax hold_;
  std::vector<long> level_frames_;
  // Threshold policy: the nodes within max_radius of the current centre, by distance.
  std::vector<int> near_nodes_;
  std::vector<double> near_distance_;
};

}  // namespace softsim::regions
