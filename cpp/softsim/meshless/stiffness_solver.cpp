#include "softsim/meshless/stiffness_solver.hpp"

#include <sstream>

#include <Eigen/Cholesky>

#include "softsim/io/errors.hpp"

namespace softsim::meshless {

std::string solver_name(SolverKind kind) {
  return kind == SolverKind::sparse_ldlt ? "sparse_ldlt" : "dense_llt";
}

void StiffnessSolver::factorize(const SparseMatrix& k, double reference_scale) {
  n_ = k.rows();
  Eigen::VectorXd pivots;
  bool ok = true;
  if (kind_ == SolverKind::sparse_ldlt) {
    sparse_.compute(k);
    ok = sparse_.info() == Eigen::Success;
    if (ok) pivots = sparse_.vectorD();
  } else {
    dense_.reset();
    dense_matrix_ = Eigen::MatrixXd(k);
    dense_ = std::make_unique<Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>>>(dense_matrix_);
    ok = dense_->info() == Eigen::Success;
    if (ok) pivots = dense_->matrixLLT().diagonal().array().square();
  }
  const double scale = reference_scale > 0 ? reference_scale : k.diagonal().cwiseAbs().maxCoeff();
  const double lo = ok ? pivots.minCoeff() : 0.0;
  pivot_ratio_ = scale > 0 ? lo / scale : 0.0;
  // Round-off leaves a rigid-body mode with a pivot near eps · scale; anything that small (or
  // negative) means K is singular or indefinite, and the solution would be garbage.
  if (!ok || !(pivot_ratio_ > kMinPivotRatio) || !pivots.allFinite()) {
    std::ostringstream os;
    os.precision(3);
    os << "stiffness factorisation (" << solver_name(kind_) << ", " << n_
       << " dofs): K is singular or not positive definite (smallest pivot " << pivot_ratio_
       << " x the largest stiffness diagonal, limit " << kMinPivotRatio
       << "); are the essential boundary conditions enough to stop rigid-body motion?";
    throw NumericalError(os.str());
  }
}

Eigen::MatrixXd StiffnessSolver::solve(const Eigen::MatrixXd& f) const {
  Eigen::MatrixXd u = kind_ == SolverKind::sparse_ldlt ? Eigen::MatrixXd(sparse_.solve(f))
                                                       : Eigen::MatrixXd(dense_->solve(f));
  if (!u.allFinite()) throw NumericalError("stiffness solve: non-finite displacement");
  return u;
}

}  // namespace softsim::meshless
