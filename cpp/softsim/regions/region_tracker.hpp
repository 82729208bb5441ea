#pragma once
// The linked regions of a live scene (001 §5): which primary region is active, and the hand-over
// between regions. The active region's interior holds the contact triangle; it is centred on the
// contact's nearest node and sized by the policy (AdaptiveRadius) from the current deformation.
// When the contact slides out of the interior or the size changes, the next region takes over
// the state the current one publishes (its secondary brought up to date first, the central
// difference resumed) so the force does not jump. Regions built for the current contact node are
// kept, so a size that comes back is not built again (001 precomputes one system per size).
#include <array>
#include <map>
#include <memory>
#include <vector>

#include "softsim/multirate/region_layout.hpp"
#include "softsim/regions/region_solver.hpp"

namespace softsim::regions {

struct RegionBuilds {
  long builds = 0;        // regions built
  long switches = 0;      // hand-overs between regions (moves and size changes)
  double seconds = 0, max_seconds = 0;  // building them
};

class RegionTracker {
 public:
  // InputError for bad options (a maximum radius below the radius, fewer than 2 levels, ...).
  RegionTracker(const mesh::TetMesh& mesh, const hybrid::DhdConfig& model, std::vector<fem::ElementKind> kinds,
                double dt, int substeps, const RegionOptions& options);

  // Makes the active region one that suits the contact on `nodes` with `weights` (barycentric):
  // centred on the node of largest weight, whose neighbours are always interior.
  void follow(const std::array<int, 3>& nodes, const Eigen::Vector3d& weights, long frame);
  // One frame of the active region (none yet: nothing moves).
  void frame(const std::vector<dynamics::AppliedForce>& forces);
  // Every region back to rest (recovery from a numerical failure).
  void back_to_rest();
  const double* displacement() const { return active_ ? active_->displacement() : rest_.data(); }
  const RegionSolver* active() const { return active_; }
  double active_radius() const { return active_ ? active_->region().radius : 0.0; }
  const RegionBuilds& builds() const { return builds_; }
  // Statistics summed over every region used, for the frames each was active.
  RegionStats totals() const;
  // Frames spent at each size level (index: level).
  const std::vector<long>& frames_per_level() const { return level_frames_; }

 private:
  int target_level(int centre, long frame);
  double level_radius(int level) const;
  void activate(int centre, int level);

  const mesh::TetMesh* mesh_;
  hybrid::DhdConfig model_;
  std::vector<fem::ElementKind> kinds_;
  double dt_;
  int substeps_;
  RegionOptions options_;
  std::vector<double> masses_;
  std::unique_ptr<LinearModel> linear_;
  std::vector<double> rest_;
  // Regions built around the current contact node, by size level.
  int centre_ = -1;
  std::map<int, std::unique_ptr<RegionSolver>> built_;
  RegionSolver* active_ = nullptr;
  int active_level_ = -1;
  RegionStats active_from_;  // the active region's statistics when it became active
  RegionStats retired_;      // summed over the regions' earlier active spells
  RegionBuilds builds_;
  multirate::SlidingMax hold_;
  std::vector<long> level_frames_;
  // Threshold policy: the nodes within max_radius of the current centre, by distance.
  std::vector<int> near_nodes_;
  std::vector<double> near_distance_;
};

}  // namespace softsim::regions
