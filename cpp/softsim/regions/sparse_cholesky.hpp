#pragma once
// The secondary region's sparse Cholesky factorisation, computed once and solved many times:
// CHOLMOD's supernodal factorisation (Debian's SuiteSparse, already there for Ceres) when the
// build found it, else Eigen's simplicial one after an AMD ordering (multirate::SpdSolver). On
// a refined organ (50 000 unknowns) the supernodal factorisation is the difference between
// seconds and minutes of set-up. Solves reuse their workspace: no allocation after the first.
#include <memory>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace softsim::regions {

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // A symmetric positive definite matrix (both triangles stored). NumericalError naming `what`
  // when it is not positive definite.
  void factorize(const Eigen::SparseMatrix<double>& A, const std::string& what);
  // x holds the right-hand side(s) on entry and the solution(s) on return.
  void solve_in_place(Eigen::VectorXd& x);
  void solve_in_place(Eigen::MatrixXd& X);
  int size() const { return size_; }
  // "cholmod supernodal" or "eigen simplicial".
  static const char* backend();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int size_ = 0;
};

}  // namespace softsim::regions
