#pragma once
// Linked asynchronous FEM regions (001 §5).
//
// The primary region (the nodes nearest the contact node) is solved every haptic frame; each
// secondary region every `every`-th frame with its own solver and the step every * frame_step.
// A region is solved with 001 eq. 7: its rows of the system, the values of every other node
// moved to the right-hand side, so the border ("connection") nodes carry the deformation
// across regions updated at different rates.
//
// Order within a frame: the primary region first (seeing the secondary regions' published
// values), then every secondary region due this frame, outward (each seeing the primary's new
// values and the other regions' published values).
//
// Published values of a secondary region (what its neighbours see):
//   interpolate = false: its last solution, held until the next update (the "moving wall"
//                        of 001 §5 that makes the force jump at every update);
//   interpolate = true:  001 Fig. 4: between its updates k-1 and k the values move linearly
//                        from solution k-1 to solution k over the next `every` frames, so they
//                        are continuous but one update (every frames) late.
//
// Regions solved every frame that follow the primary region directly and share its solver are
// merged into it (one solve): with every region at the full rate the scheme is the whole model.
// (merge_full_rate = false keeps them separate: one block Gauss-Seidel sweep per frame.)
//
// Adaptable primary region (001 §5, Fig. 5): before each frame the policy sets the primary
// size from the current deformation; nodes that join the primary region start from their
// published displacement (and, when interpolated, the interpolation's velocity), nodes that
// leave it hold their displacement until the first secondary region's next update.
#include <memory>
#include <string>
#include <vector>

#include "softsim/multirate/block_integrator.hpp"
#include "softsim/multirate/frame_stepper.hpp"
#include "softsim/multirate/region_layout.hpp"

namespace softsim::multirate {

struct SecondaryRegionSpec {
  int nodes = 0;   // node count; 0 = every node not yet assigned (only the last region)
  int every = 10;  // solved every `every`-th haptic frame
  SolverSpec solver;
};

// The regions themselves: their sizes, rates and solvers and how they exchange values.
struct AsyncRegionsSpec {
  PrimarySizePolicy primary;
  SolverSpec primary_solver;
  std::vector<SecondaryRegionSpec> secondary;
  bool interpolate = true;
  // Solve leading full-rate regions with the primary in one system (true), or in turn like
  // any other region (false: isolates the cost of the region-by-region exchange of eq. 7).
  bool merge_full_rate = true;
};

// The regions and the settings they share with the whole model of the same run (a comparison
// keeps those once, for both).
struct AsyncSpec : AsyncRegionsSpec {
  double frame_step = 1e-3;  // s, 1 / haptic rate
  LinearSolverKind linear_solver = LinearSolverKind::kSparse;
  bool enforce_stability_limit = true;
};

class AsyncSolver : public FrameStepper {
 public:
  // Throws InputError for an inconsistent layout (sizes that do not cover the free nodes, an
  // adaptive range outside the model) and SetupError for an explicit region above its stability
  // limit (blaming that region's solver).
  AsyncSolver(const ReducedSystem& system, int contact_free_node, const AsyncSpec& spec);
  AsyncSolver(const AsyncSolver&) = delete;
  AsyncSolver& operator=(const AsyncSolver&) = delete;

  void reset() override;
  void advance(const Eigen::VectorXd& contact_force) override;
  double contact_displacement(int d) const override { return u_[d]; }  // the contact node is node 0
  int dofs_per_node() const override { return dpn_; }
  int primary_nodes() const override { return primary_end_; }

  // Displacement of every free node as its neighbours see it now, in the caller's free-node
  // numbering (size: free DOFs).
  void published_displacement(Eigen::VectorXd& out) const;
  // Number of (re)factorised blocks held for the adaptable region sizes.
  int blocks() const { return static_cast<int>(owned_.size()); }
  // Smallest explicit stability limit over the blocks (infinity when none is explicit).
  double smallest_stability_limit() const;

 private:
  struct Secondary {
    int every = 1;
    // One block, or (the first secondary region of an adaptive layout, which begins where the
    // primary region ends) one per primary size, by primary size - min size.
    std::vector<BlockIntegrator*> blocks;
    long last_update = 0;  // frame index of the last solve
  };

  BlockIntegrator& primary_block() { return *primary_blocks_[primary_end_ - primary_min_]; }
  BlockIntegrator& secondary_block(Secondary& s) {
    return *s.blocks[s.blocks.size() > 1 ? primary_end_ - primary_min_ : 0];
  }
  double published(int dof, long frame) const;
  void refresh_view(const BlockIntegrator& block, long frame);
  void resize_primary(int target, long frame);
  int target_primary_size(long frame) const;

  ReducedSystem system_;     // renumbered in contact-distance order
  std::vector<int> order_;   // new free node k = caller's free node order_[k]
  int dpn_ = 1;
  int nodes_ = 0;
  double frame_step_ = 0.0;
  PrimarySizePolicy policy_;
  bool adaptive_ = false;
  bool interpolate_ = true;
  int primary_min_ = 0;
  int primary_end_ = 0;  // current primary size in nodes
  std::vector<std::unique_ptr<BlockIntegrator>> owned_;
  std::vector<BlockIntegrator*> primary_blocks_;  // by primary size - min size
  std::vector<Secondary> secondary_;
  // Secondary region of each node outside the primary region: a node of the adaptive range
  // belongs to the first one whenever the primary region does not hold it (the entries of
  // primary nodes are never read).
  std::vector<int> region_of_node_;
  SlidingMax held_size_;
  Eigen::VectorXd u_, v_, u_prev_, view_, force_, previous_force_;
  long frame_ = 0;
};

}  // namespace softsim::multirate
