#pragma once
// The lowest fixed-interface vibration modes of the far field (Craig & Bampton 1968): the
// secondary region's own dofs with the interface held, K_SS φ = ω² M_SS φ, M_SS the lumped
// (diagonal) mass. Mass-normalised: Φᵀ M_SS Φ = I, Φᵀ K_SS Φ = Ω². Few modes are wanted (a
// handful to a few dozen), so a block subspace iteration with the far field's Cholesky factor,
// already computed for the condensation, finds them; a small far field is solved densely.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "softsim/regions/sparse_cholesky.hpp"

namespace softsim::regions {

struct FarFieldModes {
  Eigen::MatrixXd phi;     // one mode per column (n × m), mass-normalised
  Eigen::VectorXd omega2;  // ω² per mode, ascending (1/s²)
};

// The `count` lowest modes of (K, diag(mass)) (at most K's size). `factor` holds K's Cholesky
// factorisation. NumericalError when the iteration does not converge.
FarFieldModes lowest_modes(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& mass, SparseCholesky& factor,
                           int count);

}  // namespace softsim::regions
