#include "softsim/meshless/rpim_shape.hpp"

#include <cmath>
#include <sstream>

#include "softsim/io/errors.hpp"

namespace softsim::meshless {

namespace {

// The support is shifted to x and scaled by its largest node distance s before the solve:
// the MQ interpolant is invariant under this map when the shape length is scaled with it
// (R scales by s^(2q), a common factor that cancels in Φ = Rᵀ R_s⁻¹), and the polynomial
// space is invariant under affine maps. The scaling only balances the R and P blocks.
double local_frame(const Eigen::Vector3d& x, const Eigen::Ref<const Eigen::MatrixX3d>& support,
                   Eigen::MatrixX3d& local) {
  local = support.rowwise() - x.transpose();
  double s = local.rowwise().norm().maxCoeff();
  if (!(s > 0)) s = 1.0;  // a single node at x
  local /= s;
  return s;
}

std::string point_text(const Eigen::Vector3d& x) {
  std::ostringstream os;
  os.precision(6);
  os << "(" << x.x() << ", " << x.y() << ", " << x.z() << ") m";
  return os.str();
}

}  // namespace

RpimShapeEvaluator::RpimShapeEvaluator(const RbfParams& params) : params_(params) {}

void RpimShapeEvaluator::build_moment_matrix(const Eigen::Ref<const Eigen::MatrixX3d>& local,
                                             double c2, Eigen::MatrixXd& g) const {
  const int n = static_cast<int>(local.rows());
  const int m = params_.polynomial_terms();
  g.setZero(n + m, n + m);
  // Squared distances first, then one vectorised power over the block, as exp(q log(·)): the
  // powers are the bulk of the shape-function cost, and in the scaled frame (r² + c² = O(1))
  // this costs no accuracy.
  auto r = g.topLeftCorner(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) r(i, j) = (local.row(i) - local.row(j)).squaredNorm();
  r = (params_.q * (r.array() + c2).log()).exp().matrix();  // 002 eq. 13: R_s
  if (m == 4) {
    for (int i = 0; i < n; ++i) {
      g(i, n) = g(n, i) = 1.0;
      for (int k = 0; k < 3; ++k) g(i, n + 1 + k) = g(n + 1 + k, i) = local(i, k);
    }
  }
}

void RpimShapeEvaluator::evaluate(const Eigen::Vector3d& x,
                                  const Eigen::Ref<const Eigen::MatrixX3d>& support,
                                  bool with_gradient, ShapeValues& out) {
  const int n = static_cast<int>(support.rows());
  const int m = params_.polynomial_terms();
  if (n == 0) throw NumericalError("RPIM shape functions at " + point_text(x) + ": empty support domain");
  const double s = local_frame(x, support, local_);
  const double c = params_.shape_length() / s;
  const double c2 = c * c;
  const double q = params_.q;
  build_moment_matrix(local_, c2, g_);

  // Right-hand sides: [R(x); p(x)] and its x, y, z derivatives at the local origin (= x).
  // Because G is symmetric, Φᵀ = G⁻¹ [R(x); p(x)] (002 eq. 17 transposed).
  const int cols = with_gradient ? 4 : 1;
  rhs_.setZero(n + m, cols);
  log_r2c2_ = (local_.rowwise().squaredNorm().array() + c2).log();
  rhs_.col(0).head(n) = (q * log_r2c2_).exp().matrix();
  if (with_gradient) {
    // ∂/∂x_k (|x - x_i|² + c²)^q = 2q (r² + c²)^(q-1) (x_k - x_ik), with x at the origin.
    gradient_factor_ = -2.0 * q * ((q - 1.0) * log_r2c2_).exp();
    for (int k = 0; k < 3; ++k) rhs_.col(1 + k).head(n) = (gradient_factor_ * local_.col(k).array()).matrix();
  }
  if (m == 4) {
    rhs_(n, 0) = 1.0;  // p(0) = [1, 0, 0, 0]
    if (with_gradient)
      for (int k = 0; k < 3; ++k) rhs_(n + 1 + k, 1 + k) = 1.0;
  }

  lu_.compute(g_);
  const double rcond = lu_.rcond();
  const double condition = rcond > 0 ? 1.0 / rcond : INFINITY;
  if (!(condition <= params_.max_moment_condition)) {
    std::ostringstream os;
    os.precision(3);
    os << "RPIM shape functions at " << point_text(x) << ": moment matrix of " << n
       << " nodes" << (m ? " + 4 linear terms" : "") << " is singular (condition estimate "
       << condition << " exceeds the limit " << params_.max_moment_condition << "; q = " << q
       << ", alpha_c = " << params_.alpha_c << ", d_c = " << params_.d_c << " m)";
    throw NumericalError(os.str());
  }
  solution_ = lu_.solve(rhs_);
  if (!solution_.allFinite())
    throw NumericalError("RPIM shape functions at " + point_text(x) + ": non-finite shape function values");

  out.moment_condition = condition;
  out.phi = solution_.col(0).head(n);
  const double partition_error = std::abs(out.phi.sum() - 1.0);
  if (!(partition_error <= params_.max_partition_error)) {
    std::ostringstream os;
    os.precision(3);
    os << "RPIM shape functions at " << point_text(x) << ": the " << n
       << " support nodes do not reproduce a constant (|sum phi - 1| = " << partition_error
       << " exceeds the limit " << params_.max_partition_error << "; q = " << q << ", alpha_c = "
       << params_.alpha_c << ", d_c = " << params_.d_c
       << " m): enlarge the support or add the linear polynomial";
    throw NumericalError(os.str());
  }
  if (with_gradient) out.dphi = solution_.block(0, 1, n, 3) / s;
  else out.dphi.resize(0, 3);
}

}  // namespace softsim::meshless
