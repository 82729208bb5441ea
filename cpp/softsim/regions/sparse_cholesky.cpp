#include "softsim/regions/sparse_cholesky.hpp"

#include <vector>

#include "softsim/io/errors.hpp"

#ifdef SOFTSIM_HAVE_CHOLMOD
#include <cholmod.h>
#else
#include "softsim/multirate/spd_solver.hpp"
#endif

namespace softsim::regions {

#ifdef SOFTSIM_HAVE_CHOLMOD

struct SparseCholesky::Impl {
  cholmod_common common;
  cholmod_factor* factor = nullptr;
  // Solve workspace, kept between solves (cholmod_solve2 reallocates only on a size change).
  cholmod_dense* x = nullptr;
  cholmod_dense* y = nullptr;
  cholmod_dense* e = nullptr;
  Impl() {
    cholmod_start(&common);
    common.supernodal = CHOLMOD_SUPERNODAL;
  }
  ~Impl() {
    cholmod_free_dense(&x, &common);
    cholmod_free_dense(&y, &common);
    cholmod_free_dense(&e, &common);
    cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
  void solve(double* data, int rows, int cols) {
    cholmod_dense b;
    b.nrow = rows;
    b.ncol = cols;
    b.nzmax = static_cast<std::size_t>(rows) * cols;
    b.d = rows;
    b.x = data;
    b.z = nullptr;
    b.xtype = CHOLMOD_REAL;
    b.dtype = CHOLMOD_DOUBLE;
    if (!cholmod_solve2(CHOLMOD_A, factor, &b, nullptr, &x, nullptr, &y, &e, &common))
      throw NumericalError("regions: sparse solve failed (CHOLMOD status " + std::to_string(common.status) + ")");
    const double* out = static_cast<const double*>(x->x);
    for (int c = 0; c < cols; ++c)
      for (int r = 0; r < rows; ++r) data[static_cast<std::size_t>(c) * rows + r] = out[static_cast<std::size_t>(c) * x->d + r];
  }
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;

const char* SparseCholesky::backend() { return "cholmod supernodal"; }

void SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A, const std::string& what) {
  size_ = static_cast<int>(A.rows());
  if (size_ == 0) return;
  // CHOLMOD reads the lower triangle of a symmetric matrix in compressed columns.
  Eigen::SparseMatrix<double> lower = A.triangularView<Eigen::Lower>();
  lower.makeCompressed();
  std::vector<int> p(lower.outerIndexPtr(), lower.outerIndexPtr() + size_ + 1);
  std::vector<int> i(lower.innerIndexPtr(), lower.innerIndexPtr() + lower.nonZeros());
  std::vector<double> v(lower.valuePtr(), lower.valuePtr() + lower.nonZeros());
  cholmod_sparse s;
  s.nrow = s.ncol = size_;
  s.nzmax = lower.nonZeros();
  s.p = p.data();
  s.i = i.data();
  s.nz = nullptr;
  s.x = v.data();
  s.z = nullptr;
  s.stype = -1;  // symmetric, lower triangle
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  cholmod_common& c = impl_->common;
  cholmod_free_factor(&impl_->factor, &c);
  impl_->factor = cholmod_analyze(&s, &c);
  if (!impl_->factor) throw NumericalError(what + ": CHOLMOD analysis failed (status " + std::to_string(c.status) + ")");
  cholmod_factorize(&s, impl_->factor, &c);
  if (c.status == CHOLMOD_NOT_POSDEF || impl_->factor->minor < impl_->factor->n)
    throw NumericalError(what + ": system matrix is not positive definite (CHOLMOD, column " +
                         std::to_string(impl_->factor->minor) + ")");
  if (c.status < CHOLMOD_OK) throw NumericalError(what + ": CHOLMOD factorisation failed (status " + std::to_string(c.status) + ")");
}

void SparseCholesky::solve_in_place(Eigen::VectorXd& x) {
  if (size_ > 0) impl_->solve(x.data(), size_, 1);
}

void SparseCholesky::solve_in_place(Eigen::MatrixXd& X) {
  if (size_ == 0 || X.cols() == 0) return;
  impl_->solve(X.data(), size_, static_cast<int>(X.cols()));
}

#else  // Eigen's simplicial Cholesky after an AMD ordering

struct SparseCholesky::Impl {
  multirate::SpdSolver solver;
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;

const char* SparseCholesky::backend() { return "eigen simplicial"; }

void SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A, const std::string& what) {
  size_ = static_cast<int>(A.rows());
  if (size_ > 0) impl_->solver.factorize(A, multirate::LinearSolverKind::kSparse, what);
}

void SparseCholesky::solve_in_place(Eigen::VectorXd& x) {
  if (size_ > 0) impl_->solver.solve_in_place(x);
}

void SparseCholesky::solve_in_place(Eigen::MatrixXd& X) {
  if (size_ == 0) return;
  for (Eigen::Index c = 0; c < X.cols(); ++c) {
    Eigen::VectorXd col = X.col(c);
    impl_->solver.solve_in_place(col);
    X.col(c) = col;
  }
}

#endif

}  // namespace softsim::regions
