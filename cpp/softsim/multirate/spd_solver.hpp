#pragma once
// A symmetric positive definite system factorised once in setup and solved in place every
// frame without allocating (the 001 §4 "direct elimination" of a constant system matrix).
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "softsim/multirate/solver_spec.hpp"

namespace softsim::multirate {

class SpdSolver {
 public:
  // Throws NumericalError when the matrix is not positive definite; `what` names it.
  void factorize(const Eigen::SparseMatrix<double>& matrix, LinearSolverKind kind, const std::string& what);
  // x holds the right-hand side on entry and the solution on return.
  void solve_in_place(Eigen::Ref<Eigen::VectorXd> x) const;

 private:
  LinearSolverKind kind_ = LinearSolverKind::kSparse;
  int size_ = 0;
  Eigen::LLT<Eigen::MatrixXd> dense_;
  // Natural ordering on a matrix we permute ourselves: Eigen's own permuted solve allocates.
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> sparse_;
  std::vector<int> order_;  // permuted row k is original row order_[k]
  mutable Eigen::VectorXd scratch_;
};

}  // namespace softsim::multirate
