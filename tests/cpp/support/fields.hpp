#pragma once
// Fields, scene pieces, runs and energy checks shared by the FEM, dynamics and hybrid test files.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/dynamics/stable_step.hpp"
#include "softsim/dynamics/static_solver.hpp"
#include "softsim/dynamics/scene.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/mesh/tet_mesh.hpp"

#include "support/scenes.hpp"

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
  set.compute(u.data(), st);
  std::vector<double> f(u.size());
  for (int i = 0; i < set.num_nodes(); ++i) set.gather(i, &f[3 * i]);
  return f;
}

// The engine's tiled sweep (tiles computed in order, each node gathered right after its ready
// tile) must gather every node exactly once, never before its first tile, and give exactly the
// forces of a whole-set pass (a node gathered too early would miss a later element's
// contribution, as the buffer of a fresh set starts at zero).
inline void expect_tiled_sweep_equals_whole_pass(const mesh::TetMesh& m, const std::vector<fem::ElementKind>& kinds,
                                                 const fem::Material& mat, const std::vector<double>& u) {
  fem::ElementSet whole(m, kinds, mat, 16);
  const std::vector<double> expected = gathered_forces(whole, u);
  fem::ElementSet tiled(m, kinds, mat, 16);
  ASSERT_GT(tiled.num_tiles(), 4);
  std::vector<double> f(u.size(), 0.0);
  std::vector<int> gathers(m.num_nodes(), 0);
  for (int t = 0; t < tiled.num_tiles(); ++t) {
    fem::KernelStats st;
    tiled.compute_tile(u.data(), t, st);
    for (const int* n = tiled.ready_nodes_begin(t); n != tiled.ready_nodes_end(t); ++n) {
      tiled.gather(*n, &f[3 * *n]);
      ++gathers[*n];
      EXPECT_LE(tiled.first_tile(*n), t) << "node " << *n;
    }
  }
  for (int i = 0; i < m.num_nodes(); ++i) EXPECT_EQ(gathers[i], 1) << "node " << i;
  EXPECT_EQ(f, expected);
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

// The nodes off the "boundary" set, in increasing order.
inline std::vector<int> interior_nodes(const mesh::TetMesh& m) {
  const auto& b = m.node_sets.at("boundary");
  std::vector<int> out;
  for (int i = 0; i < m.num_nodes(); ++i)
    if (!std::binary_search(b.begin(), b.end(), i)) out.push_back(i);
  return out;
}

// The patch test's load: every boundary node prescribed to u = (F − I) X, one constraint each.
inline dynamics::Scene affine_boundary_scene(const mesh::TetMesh& m, const Eigen::Matrix3d& F) {
  dynamics::Scene scene;
  for (int i : m.node_sets.at("boundary")) {
    dynamics::DisplacementConstraint c;
    c.name = "boundary";
    c.nodes = {i};
    c.displacement = (F - Eigen::Matrix3d::Identity()) * m.nodes[i];
    scene.constraints.push_back(c);
  }
  return scene;
}

inline double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// Largest componentwise |a − b| (a and b of equal length).
inline double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t q = 0; q < a.size(); ++q) m = std::max(m, std::abs(a[q] - b[q]));
  return m;
}

// An explicit run of the element set of (m, kinds, mat) from rest, or from u0 when given.
inline dynamics::ExplicitResult run_explicit(const mesh::TetMesh& m, const std::vector<fem::ElementKind>& kinds,
                                             const fem::Material& mat, const dynamics::Scene& scene,
                                             const dynamics::ExplicitOptions& opt, std::vector<double> u0 = {},
                                             int tile_nodes = 256) {
  fem::ElementSet set(m, kinds, mat, tile_nodes);
  dynamics::ExplicitSolver solver(set, dynamics::lumped_mass(m, mat.elastic.density), scene, opt);
  if (!u0.empty()) solver.set_initial_state(std::move(u0), {});
  return solver.run();
}

// Bottom clamped, top face pushed by (2, 0, −6) mm with a smooth 0.2 s ramp; 2500 steps of
// 0.9 × the critical step of the paper's material with mass damping α = 60/s, by when the run
// has settled on the static solution of the same scene.
struct DampedRun {
  dynamics::Scene scene;
  dynamics::ExplicitOptions options;
};

inline DampedRun damped_sheared_press(const mesh::TetMesh& m) {
  DampedRun run;
  run.scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero()),
                           constraint(m, "top", Eigen::Vector3d(0.002, 0, -0.006))};
  run.scene.constraints[1].ramp.duration = 0.2;
  run.scene.constraints[1].ramp.shape = dynamics::Ramp::Shape::smooth;
  run.options.dt = 0.9 * dynamics::critical_time_step(m, kPaper).dt;
  run.options.steps = 2500;
  run.options.damping_alpha = 60.0;
  return run;
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

// Undamped free vibration of a block with its bottom clamped, released from the static shape of
// a 2 mm lateral shift of its top face (a 5 % shear of the 4 cm cuboids): the run must start
// from the static strain energy, keep kinetic + strain energy within 0.2 % of its initial value
// over 3000 steps, and really vibrate.
inline void expect_free_vibration_conserves_energy(const mesh::TetMesh& m, const std::vector<fem::ElementKind>& kinds,
                                                   const fem::Material& mat) {
  dynamics::Scene load;
  load.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero()),
                      constraint(m, "top", Eigen::Vector3d(0.002, 0, 0))};
  const auto stat = dynamics::solve_static(m, kinds, mat, load, {});
  dynamics::Scene free;
  free.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero())};
  dynamics::ExplicitOptions opt;
  opt.dt = 0.9 * dynamics::critical_time_step(m, mat.elastic).dt;
  opt.steps = 3000;
  opt.energy_interval = 10;
  fem::ElementSet set(m, kinds, mat);
  dynamics::ExplicitSolver solver(set, dynamics::lumped_mass(m, mat.elastic.density), free, opt);
  solver.set_initial_state(stat.displacement, {});
  const auto r = solver.run();
  EXPECT_NEAR(r.energies.front().strain, stat.strain_energy, 1e-9 * stat.strain_energy);
  const auto drift = energy_drift(r);
  EXPECT_LT(drift.worst, 2e-3);
  EXPECT_GT(drift.max_kinetic, 0.5 * drift.initial) << "the block must actually vibrate";
}

}  // namespace softsim::test_scenes
