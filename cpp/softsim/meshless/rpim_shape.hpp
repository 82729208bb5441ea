#pragma once
// Radial point interpolation shape functions (002 §2.2, eqs. 11–17; Liu & Gu's RPIM).
//
//   u(x) = Σ_i R_i(x) a_i + Σ_j p_j(x) b_j                                   002 eq. 11
//   R_i(x) = (r_i² + (α_c d_c)²)^q   (multiquadric, MQ)                       002 §2.2
//
// Without the polynomial terms (the paper's choice, eq. 12) the moment matrix is R_s
// (eq. 14) and Φ(x) = Rᵀ(x) R_s⁻¹ (eq. 17). With linear augmentation (p = [1, x, y, z]) the
// coefficients are constrained by Pᵀ a = 0 and the moment matrix becomes
//   G = [R_s  P; Pᵀ  0],   [Φ(x)  ·] = [Rᵀ(x)  pᵀ(x)] G⁻¹,
// which reproduces every linear field exactly and so passes the patch test.
// Both variants interpolate (Kronecker delta property: φ_i(x_j) = δ_ij).
#include <Eigen/Core>
#include <Eigen/LU>

namespace softsim::meshless {

enum class PolynomialBasis { none, linear };

struct RbfParams {
  double alpha_c = 1.0;        // dimensionless shape factor α_c (002: 1.0)
  double d_c = 0.002;          // characteristic length d_c in metres (resolved by the caller)
  double q = 1.03;             // MQ exponent (002: 1.03)
  PolynomialBasis polynomial = PolynomialBasis::none;
  // Largest accepted 1-norm condition number of the moment matrix; above it the shape
  // functions are garbage and evaluation throws NumericalError instead.
  double max_moment_condition = 1e14;
  // Largest accepted |Σφ_i(x) - 1|. Pure MQ shape functions reproduce a constant only
  // approximately (about 1e-3 with the paper's parameters); an error of several percent means
  // the support is too small or the basis degenerate and the model cannot even translate
  // rigidly, so evaluation throws NumericalError rather than return such shape functions.
  double max_partition_error = 0.05;

  double shape_length() const { return alpha_c * d_c; }
  int polynomial_terms() const { return polynomial == PolynomialBasis::linear ? 4 : 0; }
};

// Shape function values (and gradients) of the n support nodes at one point.
struct ShapeValues {
  Eigen::VectorXd phi;    // n
  Eigen::MatrixX3d dphi;  // n × 3: ∂φ_i/∂x, ∂φ_i/∂y, ∂φ_i/∂z
  double moment_condition = 0;  // 1-norm condition estimate of the moment matrix
};

// Evaluates RPIM shape functions. Holds work arrays, so one evaluator per thread.
class RpimShapeEvaluator {
 public:
  explicit RpimShapeEvaluator(const RbfParams& params);

  // support: n × 3 node coordinates (m). Throws NumericalError when the moment matrix is
  // singular or its condition number exceeds params.max_moment_condition, or when the shape
  // functions miss the partition of unity by more than params.max_partition_error.
  void evaluate(const Eigen::Vector3d& x, const Eigen::Ref<const Eigen::MatrixX3d>& support,
                bool with_gradient, ShapeValues& out);

 private:
  void build_moment_matrix(const Eigen::Ref<const Eigen::MatrixX3d>& local, double c2,
                           Eigen::MatrixXd& g) const;

  RbfParams params_;
  // Work arrays kept between calls: they are reallocated only when the support size changes
  // from one point to the next.
  Eigen::MatrixX3d local_;
  Eigen::MatrixXd g_;
  Eigen::ArrayXd log_r2c2_;         // log(r_i² + c²) of every support node
  Eigen::ArrayXd gradient_factor_;  // -2q (r_i² + c²)^(q-1)
  Eigen::MatrixXd rhs_;             // [R(x); p(x)] and its derivatives
  Eigen::MatrixXd solution_;        // G⁻¹ rhs_: Φᵀ and its derivatives
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
};

}  // namespace softsim::meshless
