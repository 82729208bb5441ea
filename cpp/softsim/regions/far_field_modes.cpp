#include "softsim/regions/far_field_modes.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "softsim/io/errors.hpp"

namespace softsim::regions {

namespace {

// M^-1/2 K M^-1/2 is symmetric with the same eigenvalues; its eigenvectors scaled by M^-1/2 are
// the mass-normalised modes.
FarFieldModes dense_modes(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& mass, int count) {
  const Eigen::VectorXd s = mass.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd A = s.asDiagonal() * Eigen::MatrixXd(K) * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
  if (eig.info() != Eigen::Success) throw NumericalError("regions: far-field modes: the dense eigensolver failed");
  return {s.asDiagonal() * eig.eigenvectors().leftCols(count), eig.eigenvalues().head(count)};
}

}  // namespace

FarFieldModes lowest_modes(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& mass, SparseCholesky& factor,
                           int count) {
  const int n = static_cast<int>(K.rows());
  count = std::min(count, n);
  if (count <= 0) return {Eigen::MatrixXd(n, 0), Eigen::VectorXd(0)};
  const int p = std::min(n, std::max(2 * count, count + 8));  // a guard block speeds convergence
  if (n <= 1500 || p == n) return dense_modes(K, mass, count);
  // Subspace iteration (Bathe): X ← K⁻¹ M X, then Rayleigh–Ritz on the block. A fixed start
  // (a smooth ramp per column plus a seeded pattern) keeps the result reproducible.
  Eigen::MatrixXd X(n, p);
  for (int j = 0; j < p; ++j)
    for (int i = 0; i < n; ++i) X(i, j) = std::sin(0.37 * (j + 1) * (i + 1) + 0.11 * j) + (i % (j + 2) == 0 ? 1.0 : 0.0);
  Eigen::VectorXd previous = Eigen::VectorXd::Constant(count, -1.0);
  for (int it = 0; it < 300; ++it) {
    X = mass.asDiagonal() * X;
    factor.solve_in_place(X);
    const Eigen::MatrixXd Kr = X.transpose() * (K * X);
    const Eigen::MatrixXd Mr = X.transpose() * mass.asDiagonal() * X;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (Kr + Kr.transpose()),
                                                                        0.5 * (Mr + Mr.transpose()));
    if (eig.info() != Eigen::Success) throw NumericalError("regions: far-field modes: the Rayleigh-Ritz step failed");
    X = X * eig.eigenvectors();
    const Eigen::VectorXd now = eig.eigenvalues().head(count);
    if (((now - previous).cwiseAbs().array() <= 1e-10 * now.cwiseAbs().array()).all())
      return {X.leftCols(count), now};
    previous = now;
  }
  throw NumericalError("regions: far-field modes: the subspace iteration did not converge in 300 iterations");
}

}  // namespace softsim::regions
