#pragma once
// Conditioning diagnostics: 2-norm condition of the (SPD) stiffness from its extreme
// eigenvalues (Lanczos with full reorthogonalisation on K for λ_max and on K⁻¹, applied through
// the existing factorisation, for λ_min), the stiffness restricted to the free degrees of freedom (the conditioning of the
// physics, without the penalty's λ), and the strain energy of rigid-body motions before any
// boundary condition (zero for shape functions that reproduce linear fields).
#include <array>
#include <vector>

#include <Eigen/Core>

#include "softsim/meshless/assembly.hpp"
#include "softsim/meshless/stiffness_solver.hpp"

namespace softsim::meshless {

struct SpectrumEstimate {
  double lambda_min = 0;
  double lambda_max = 0;
  double condition = 0;  // λ_max / λ_min
  int iterations = 0;    // Lanczos steps of the slower of the two runs
};

// K must be SPD and `factored` its factorisation. Stops when the extreme Ritz value changes by
// less than `tolerance` (relative) between steps.
SpectrumEstimate estimate_spectrum(const SparseMatrix& k, const StiffnessSolver& factored,
                                   int max_iterations = 120, double tolerance = 1e-10);

// The rows and columns of the degrees of freedom of unconstrained nodes.
SparseMatrix free_block(const SparseMatrix& k, const std::vector<int>& fixed_nodes);

struct RigidModeEnergy {
  // uᵀ K u / (|u|² · mean diag K) for the three translations and three infinitesimal rotations
  // about the centroid: 0 for an exact rigid-body mode, O(1) for a typical deformation.
  std::array<double, 6> ratio{};
  double max_ratio = 0;
};
RigidModeEnergy rigid_mode_energy(const SparseMatrix& k, const std::vector<Eigen::Vector3d>& nodes);

}  // namespace softsim::meshless
