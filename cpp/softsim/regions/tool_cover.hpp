#pragma once
// Which nodes a rigid tool touches or may touch within the next frames: the nodes the tool lists
// whose deformed position lies inside the tool or within `margin` of its surface. The linked
// regions keep all of them in the primary region's interior (RegionTracker::cover), because the
// tool's contact acts only there; the margin is how far a node may move towards the tool before
// the region is checked again (the next frame).
#include <vector>

#include <Eigen/Core>

#include "softsim/dynamics/scene.hpp"

namespace softsim::regions {

// The tool's listed nodes (global) at signed distance < `margin` from the tool at `centre`, in
// the geometry X + u (u: 3 per node, global), ascending, into `out` (replaced). A bounding-box
// test first: only nodes near the tool are measured.
void tool_nodes_within(const dynamics::RigidTool& tool, const Eigen::Vector3d& centre, const double* u, double margin,
                       std::vector<int>& out);

}  // namespace softsim::regions
