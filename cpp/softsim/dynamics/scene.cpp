#include "softsim/dynamics/scene.hpp"

#include <algorithm>
#include <map>

#include "softsim/io/errors.hpp"

namespace softsim::dynamics {

double Ramp::at(double t) const {
  if (duration <= 0) return 1.0;
  const double s = std::clamp(t / duration, 0.0, 1.0);
  return shape == Shape::linear ? s : s * s * (3.0 - 2.0 * s);
}

Eigen::Vector3d ProbeSpring::tip_displacement(double t) const { return displacement * ramp.at(t); }

std::vector<ConstrainedDof> resolve_constraints(const Scene& scene, int num_nodes) {
  std::map<std::pair<int, int>, ConstrainedDof> dofs;
  for (std::size_t c = 0; c < scene.constraints.size(); ++c) {
    const DisplacementConstraint& con = scene.constraints[c];
    for (int n : con.nodes) {
      if (n < 0 || n >= num_nodes)
        throw InputError("constraint \"" + con.name + "\": node " + std::to_string(n) + " out of range");
      for (int k = 0; k < 3; ++k)
        if (con.components[k]) dofs[{n, k}] = ConstrainedDof{n, k, static_cast<int>(c), con.displacement[k]};
    }
  }
  std::vector<ConstrainedDof> out;
  out.reserve(dofs.size());
  for (const auto& [key, d] : dofs) out.push_back(d);
  return out;
}

std::vector<char> constrained_mask(const std::vector<ConstrainedDof>& dofs, int num_nodes) {
  std::vector<char> mask(3 * static_cast<std::size_t>(num_nodes), 0);
  for (const auto& d : dofs) mask[3 * d.node + d.component] = 1;
  return mask;
}

}  // namespace softsim::dynamics
