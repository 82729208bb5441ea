#pragma once
// Static equilibrium F_int(u) = R (000 eq. 24) of the same model the explicit engine runs
// (same element kinds, material, constraints, loads, gravity and probe spring), by Newton's
// method with the consistent tangent and load increments: the prescribed displacements and
// loads are scaled by k/N in increment k (ramps are ignored). Each Newton step imposes the
// constraint increment in the linear solve, and backtracks (halving) while an element would
// invert or the residual grows. Linear systems: sparse LDLᵀ (Eigen), LU as a fallback.
// When every element is linear the problem is linear: one increment, one solve K u = R, and
// no inversion check (small-strain elements ignore the deformed geometry).
#include <vector>

#include <Eigen/Core>

#include "softsim/dynamics/scene.hpp"
#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/element_kind.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::dynamics {

struct StaticOptions {
  int increments = 10;
  int max_iterations = 30;  // per increment
  double tolerance = 1e-9;  // ‖residual on free dofs‖∞ ≤ tolerance × force scale
};

struct StaticResult {
  std::vector<double> displacement;        // 3 per node
  std::vector<Eigen::Vector3d> reactions;  // per constraint: Σ (F_int − R) over its dofs
  std::vector<int> iterations;             // Newton iterations per increment
  double residual = 0;                     // final ‖r_free‖∞ (N)
  double force_scale = 0;                  // the scale the tolerance multiplies (N)
  double strain_energy = 0;                // J
  Eigen::Vector3d probe_force = Eigen::Vector3d::Zero();
  bool linear_solve = false;  // every element linear: one solve of K u = R, no increments, no inversion check
};

// Throws NumericalError when an increment does not converge or the tangent is singular (for
// example when the constraints leave a rigid motion free).
StaticResult solve_static(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds,
                          const fem::Material& material, const Scene& scene, const StaticOptions& options);

}  // namespace softsim::dynamics
