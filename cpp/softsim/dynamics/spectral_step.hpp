#pragma once
// The explicit step limit from the lumped system's largest eigenvalue: central differences
// (000 eq. 33) are stable for Δt ≤ 2/ω_max, ω_max² the largest eigenvalue of M⁻¹K with M the
// lumped mass and K the tangent stiffness, the constrained components removed. 000 eq. 34's
// Δt_cr = L_e/c (stable_step.hpp) bounds it element by element and is cheap, but one bad
// element sets it for the whole mesh: on a sliver it asks for up to 119× more steps than the
// mesh needs (results/stability/quality.md). This computes ω_max itself, by power iteration.
//
// Power iteration on the symmetric A = M^(−1/2) K M^(−1/2) (same eigenvalues as M⁻¹K), from a
// seeded random start. Its Rayleigh quotient ρ = xᵀA x never exceeds λ_max; the iteration stops
// once the residual ‖A x − ρ x‖ ≤ tolerance · ρ and takes λ = ρ + ‖A x − ρ x‖ as the estimate.
// Always λ ≤ λ_max (1 + tolerance), so Δt_cr = 2/√λ is at most tolerance/2 (relative) below the
// true limit. Some eigenvalue lies within the residual of ρ; when the top one is isolated
// (a sliver's mode) that is λ_max, so λ ≥ λ_max and Δt_cr is not above the limit. When the top
// eigenvalues cluster closer than the residual (a regular mesh), ρ can settle among them and
// Δt_cr exceed the limit, by less than the tolerance in practice (tests/cpp/test_spectral_step.cpp:
// 5e-6 relative at tolerance 1e-4 on a regular block; results/stability/quality.md: at most 8e-4
// at the default 1e-3). The step used is solver.safety_factor ×
// Δt_cr (0.9 by default) as for the altitude estimate: that factor is the safety margin.
//
// K is assembled once at the given state (fem::Assembler: every element kind, ANP's nodal
// volumetric part included); at rest it is the small-strain stiffness of every kind. The probe
// spring and rigid-tool contact are left out (kinematic contact does not change the step; a
// probe spring of stiffness k adds at most k / m to its node's row).
#include <vector>

#include <Eigen/Sparse>

#include "softsim/dynamics/scene.hpp"
#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/element_kind.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::dynamics {

struct PowerIterationOptions {
  double tolerance = 1e-3;     // relative residual ‖A x − ρ x‖ / ρ at which the iteration stops
  int max_iterations = 50000;  // then the estimate ρ + residual is used as it stands (converged = false)
  unsigned seed = 1;           // of the random start (fixed: the same mesh gives the same step)
};

struct SpectralStep {
  double dt = 0;         // Δt_cr = 2 / ω_max (s)
  double omega_max = 0;  // √(ρ + residual) (rad/s)
  double rayleigh = 0;   // ρ ≤ λ_max (1/s²)
  double residual = 0;   // ‖A x − ρ x‖ (1/s²)
  int iterations = 0;
  bool converged = false;
  double tolerance = 0;
};

// On an assembled symmetric K (3 dofs per node), lumped `mass` per node and a per-dof mask of
// constrained components (removed, as are the dofs of massless nodes). NumericalError when the
// free system has no positive eigenvalue.
SpectralStep power_iteration_step(const Eigen::SparseMatrix<double>& K, const std::vector<double>& mass,
                                  const std::vector<char>& constrained, const PowerIterationOptions& options = {});

// The same with K the tangent of `kinds` and `material` at displacement `u` (3 per node; null:
// at rest), M the lumped mass of the material's density, and the scene's constraints.
SpectralStep power_iteration_step(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds,
                                  const fem::Material& material, const Scene& scene, const double* u = nullptr,
                                  const PowerIterationOptions& options = {});

}  // namespace softsim::dynamics
