#pragma once
// Fields, scene pieces and energy checks shared by the FEM and dynamics test files.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/dynamics/scene.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::test_scenes {

// u = (F − I) X at every node.
inline std::vector<double> affine_field(const mesh::TetMesh& m, const Eigen::Matrix3d& F) {
  std::vector<double> u(3 * m.nodes.size());
  for (int i = 0; i < m.num_nodes(); ++i) {
    const Eigen::Vector3d d = (F - Eigen::Matrix3d::Identity()) * m.nodes[i];
    for (int k = 0; k < 3; ++k) u[3 * i + k] = d[k];
  }
  return u;
}

// The nodal internal forces of the explicit engine's element set at u (element and node phase).
inline std::vector<double> gathered_forces(fem::ElementSet& set, const std::vector<double>& u) {
  fem::KernelStats st;
  set.compute(u.data(), 0, set.padded_size(), st);
  std::vector<double> f(u.size());
  for (int i = 0; i < set.num_nodes(); ++i) set.gather(i, &f[3 * i]);
  return f;
}

inline dynamics::DisplacementConstraint constraint(const mesh::TetMesh& m, const std::string& set, Eigen::Vector3d d,
                                                   std::array<bool, 3> comps = {true, true, true}) {
  dynamics::DisplacementConstraint c;
  c.name = set;
  c.nodes = m.node_sets.at(set);
  c.displacement = d;
  c.components = comps;
  return c;
}

inline double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// Energy of a free vibration: E0 = kinetic + strain at the first sample, the largest relative
// departure from it, and the largest kinetic energy (that the body really moved).
struct EnergyDrift {
  double initial = 0;
  double worst = 0;
  double max_kinetic = 0;
};

inline EnergyDrift energy_drift(const dynamics::ExplicitResult& r) {
  EnergyDrift d;
  d.initial = r.energies.front().kinetic + r.energies.front().strain;
  for (const auto& s : r.energies) {
    d.worst = std::max(d.worst, std::abs(s.kinetic + s.strain - d.initial) / d.initial);
    d.max_kinetic = std::max(d.max_kinetic, s.kinetic);
  }
  return d;
}

}  // namespace softsim::test_scenes
