#include "softsim/multirate/spd_solver.hpp"

#include <Eigen/OrderingMethods>

#include "softsim/io/errors.hpp"

namespace softsim::multirate {

void SpdSolver::factorize(const Eigen::SparseMatrix<double>& matrix, LinearSolverKind kind, const std::string& what) {
  kind_ = kind;
  size_ = static_cast<int>(matrix.rows());
  scratch_.setZero(size_);
  if (kind == LinearSolverKind::kDense) {
    dense_.compute(Eigen::MatrixXd(matrix));
    if (dense_.info() != Eigen::Success)
      throw NumericalError(what + ": system matrix is not positive definite (dense Cholesky failed)");
    return;
  }
  // Fill-reducing ordering. Eigen's Cholesky factorises A twisted by P^-1 where P is what the
  // ordering returns, so original row i goes to position P^-1(i): permuted row k is P(k).
  Eigen::AMDOrdering<int> amd;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm;
  amd(matrix.selfadjointView<Eigen::Lower>(), perm);
  order_.assign(perm.indices().data(), perm.indices().data() + size_);
  Eigen::SparseMatrix<double> permuted(size_, size_);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(matrix.nonZeros());
  std::vector<int> rank(size_);
  for (int k = 0; k < size_; ++k) rank[order_[k]] = k;
  for (int c = 0; c < matrix.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(matrix, c); it; ++it)
      triplets.emplace_back(rank[it.row()], rank[c], it.value());
  permuted.setFromTriplets(triplets.begin(), triplets.end());
  sparse_.compute(permuted);
  if (sparse_.info() != Eigen::Success)
    throw NumericalError(what + ": system matrix is not positive definite (sparse Cholesky failed)");
}

void SpdSolver::solve_in_place(Eigen::Ref<Eigen::VectorXd> x) const {
  if (kind_ == LinearSolverKind::kDense) {
    dense_.matrixL().solveInPlace(x);
    dense_.matrixU().solveInPlace(x);
    return;
  }
  for (int k = 0; k < size_; ++k) scratch_[k] = x[order_[k]];
  sparse_.matrixL().solveInPlace(scratch_);
  sparse_.matrixU().solveInPlace(scratch_);
  for (int k = 0; k < size_; ++k) x[order_[k]] = scratch_[k];
}

}  // namespace softsim::multirate
