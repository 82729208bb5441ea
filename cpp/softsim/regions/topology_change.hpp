#pragma once
// What a topology change tells the linked regions (RegionTracker::topology_changed): the
// elements a cut took out, and the elements whose corners or shape changed (a cut that separates
// along faces by duplicating nodes re-points elements to new nodes). Removed elements inside
// the primary region are the explicit engine's local update (000's claim for explicit
// methods); anything that reaches the secondary region invalidates its factorisation and its
// condensed interface, which are built anew (the cost 000 attributes to precomputing methods).
// Changed elements have no local update in the engine: the regions holding them are rebuilt.
#include <array>
#include <vector>

namespace softsim::regions {

struct TopologyChange {
  std::vector<int> removed;  // elements gone (original indices, ascending)
  std::vector<int> changed;  // elements still there whose corners changed
  // Node copies a separation made, (node, copy), the copies numbered after every node in order:
  // the regions' mesh (the model's, which the cut changed) has them already.
  std::vector<std::array<int, 2>> copies;
  bool empty() const { return removed.empty() && changed.empty() && copies.empty(); }
};

// What the regions' reactions to topology changes cost, summed over the run.
struct TopologyStats {
  long changes = 0;           // topology changes told
  long local_updates = 0;     // handled by the active primary engine's local update alone
  double local_seconds = 0, local_max_seconds = 0;
  long rebuilds = 0;          // the active region built anew (its secondary affected)
  double rebuild_seconds = 0, rebuild_max_seconds = 0;  // the whole rebuild, linear model included
  double secondary_seconds = 0, secondary_max_seconds = 0;  // of it: factorisation and condensation
  double linear_seconds = 0;  // of it: the small-strain stiffness of the cut mesh assembled again
  long invalidated = 0;       // cached regions (not active) dropped because a change reached them
};

}  // namespace softsim::regions
