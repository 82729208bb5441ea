#include "softsim/regions/tool_cover.hpp"

namespace softsim::regions {

void tool_nodes_within(const dynamics::RigidTool& tool, const Eigen::Vector3d& centre, const double* u, double margin,
                       std::vector<int>& out) {
  out.clear();
  Eigen::Vector3d lo, hi;
  const bool bounded = tool.bounds(centre, lo, hi);
  lo.array() -= margin;
  hi.array() += margin;
  for (std::size_t j = 0; j < tool.nodes.size(); ++j) {
    const int i = tool.nodes[j];
    const Eigen::Vector3d x = tool.positions[j] + Eigen::Vector3d(u[3 * i], u[3 * i + 1], u[3 * i + 2]);
    if (bounded && ((x.array() < lo.array()).any() || (x.array() > hi.array()).any())) continue;
    Eigen::Vector3d normal;
    if (tool.signed_distance(x, centre, normal) < margin) out.push_back(i);
  }
}

}  // namespace softsim::regions
