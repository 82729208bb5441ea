#pragma once
// Broad phase of the rigid tools' contact (issue 23): which of a tool's nodes can be inside it
// this step, so that the narrow phase (the signed distance and the projection,
// explicit_contact.cpp) runs on the nodes near the tool rather than on the whole surface.
//
// Per tool, a uniform grid over its nodes' positions x0 when the grid was built, and a candidate
// list: the nodes whose x0 lies within the margin m of the tool's bounding box when the list was
// made (B0 ⊕ m). The list stays valid while every node is within m/2 of its x0 (∞-norm) and the
// tool's box stays within B0 ⊕ m/2: a node inside the tool now lies in its box, so its x0 lies
// in B0 ⊕ m and it is listed. Each step costs one comparison per node (has any node moved m/2?)
// and the narrow phase of the candidates; the grid is rebuilt only when a node has moved m/2
// (O(nodes)), and the list is made again from the grid only when the tool has moved m/2
// (O(cells and nodes in the box)). A plane has no box: its list is the nodes within m of it,
// made by a scan. The list also keeps every entry that was in contact at the last step, so its
// force returns to zero and its work is booked as without the search. The search is
// conservative, so results are bit for bit those of a scan of every node (`enabled` false).
#include <vector>

#include <Eigen/Core>

#include "softsim/dynamics/scene.hpp"

namespace softsim::dynamics {

class ContactSearch {
 public:
  // Per tool, its contact entries (indices into the solver's entry list, ascending) with each
  // entry's node and reference position. enabled false: every entry is a candidate every step.
  void setup(const std::vector<RigidTool>& tools, std::vector<std::vector<int>> entries,
             const std::vector<int>& entry_node, const std::vector<Eigen::Vector3d>& entry_position, bool enabled);
  // Forget the grids and lists (the state went back to t = 0).
  void reset();
  // The entries of tool k that can be inside it at `centre` with nodal displacements u (3 per
  // node), ascending; `force`: the contact force of each entry at the last step (3 per entry).
  const std::vector<int>& candidates(int k, const RigidTool& tool, const Eigen::Vector3d& centre, const double* u,
                                     const double* force);
  bool enabled() const { return enabled_; }
  int rebuilds(int k) const { return tools_[k].rebuilds; }
  int queries(int k) const { return tools_[k].queries; }
  double margin(int k) const { return tools_[k].margin; }
  int listed(int k) const { return static_cast<int>(enabled_ ? tools_[k].list.size() : tools_[k].entries.size()); }

 private:
  struct ToolGrid {
    std::vector<int> entries, nodes;           // per local item: the entry and its node
    std::vector<Eigen::Vector3d> reference;    // per local item: X
    double margin = 0;
    std::vector<double> x0;                    // positions when the grid was built (3 per item)
    bool built = false, listed = false;
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    double cell = 1;
    int dims[3] = {1, 1, 1};
    std::vector<int> cell_begin, cell_items;   // CSR: cell -> local items
    Eigen::Vector3d allowed_lo, allowed_hi;    // the tool's box may move within these (B0 ⊕ m/2)
    double allowed_offset = 0;                 // plane: n·c may grow up to this
    std::vector<int> list;                     // candidate entries, ascending
    std::vector<char> mark;                    // scratch, per local item
    std::vector<int> scratch;
    int rebuilds = 0, queries = 0;
  };
  void build_grid(ToolGrid& g, const double* u);
  void make_list(ToolGrid& g, const RigidTool& tool, const Eigen::Vector3d& centre, const double* force);

  std::vector<ToolGrid> tools_;
  bool enabled_ = true;
};

}  // namespace softsim::dynamics
