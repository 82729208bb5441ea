#pragma once
// Where the asynchronous regions lie (001 §5, Fig. 2). The free nodes are renumbered by their
// distance to the contact node, so that every region is a contiguous range of node indices:
// the "border vector" of 001 §5 that keeps the begin and end node of each region. The primary
// region is the first n nodes; the secondary regions follow as consecutive ranges.
#include <vector>

#include "softsim/multirate/linear_model.hpp"

namespace softsim::multirate {

// Free nodes sorted by graph distance (element hops) from the contact node, then Euclidean
// distance, then index, so that regions grow outward through the mesh. Nodes the contact
// cannot reach through elements come last.
std::vector<int> contact_distance_order(const ReducedSystem& system, int contact_free_node);

// The border vector built region by region: the primary region's largest size, then each
// secondary region in turn. The one layout check shared by the config reader (which names the
// member at fault) and the regions solver (which refuses an inconsistent layout).
class RegionBorders {
 public:
  RegionBorders(int free_nodes, int primary_nodes);
  // Nodes the next region takes when it asks for `requested` (0: every node not yet assigned).
  int size_of(int requested) const { return requested == 0 ? remaining() : requested; }
  // Whether a region of `size` nodes fits after the last border.
  bool fits(int size) const { return size >= 1 && size <= remaining(); }
  // Appends a region of `size` nodes; call fits(size) first.
  void append(int size) { bounds_.push_back(end() + size); }
  int end() const { return bounds_.back(); }  // nodes assigned so far
  int remaining() const { return free_nodes_ - end(); }
  bool complete() const { return end() == free_nodes_; }
  // The borders: bounds()[0] is the primary size, region r spans [bounds()[r], bounds()[r + 1]).
  const std::vector<int>& bounds() const { return bounds_; }

 private:
  int free_nodes_;
  std::vector<int> bounds_;
};

// Size of the primary region (001 §5 "adaptable asynchronous regions", Fig. 5).
struct PrimarySizePolicy {
  enum class Kind {
    kFixed,      // always min_nodes
    kLinear,     // n = clamp(ceil(gradient * deformation / scale), min_nodes, max_nodes)
    kThreshold,  // n = 1 + last node (in contact-distance order) whose displacement exceeds threshold, clamped
  };
  Kind kind = Kind::kFixed;
  int min_nodes = 5;       // the fixed size; for adaptive policies the size in the undeformed state
  int max_nodes = 5;       // adaptive maximum (bounded by the computing power, 001 §6)
  double gradient = 4.0;   // nodes per scale length of deformation
  double scale = 1e-3;     // m: the deformation is measured in units of this length
  double threshold = 1e-3; // m
  // The size used is the largest target of the last hold_frames frames (0: the current target
  // only, as in 001). A region that grows at once but shrinks only after the deformation has
  // stayed small for a while follows the deformation's amplitude rather than each oscillation.
  int hold_frames = 0;

  bool adaptive() const { return kind != Kind::kFixed; }
};

// The largest value pushed over the last `window` pushes, in O(1) amortised per push and
// without allocation after construction (monotonic queue in a ring buffer).
class SlidingMax {
 public:
  explicit SlidingMax(int window = 1);
  void reset();
  // Pushes the value of step `step` (consecutive integers) and returns the window's maximum.
  int push(long step, int value);

 private:
  int window_;
  std::vector<long> steps_;
  std::vector<int> values_;
  int head_ = 0, size_ = 0;
};

// 001 Fig. 5: the linear function of the deformation size with a gradient, a minimum and a
// maximum. `deformation` is the contact node's displacement magnitude (m).
int linear_primary_size(const PrimarySizePolicy& policy, double deformation);

}  // namespace softsim::multirate
