#pragma once
// Levenberg–Marquardt least squares through Ceres (002 eqs. 30–37) for models that are linear
// in their parameters, y ≈ A b, with the analytic Jacobian A.
//
// Ceres' LEVENBERG_MARQUARDT strategy is Marquardt's damped step of 002 eq. 37: each step solves
// (AᵀA + d·D) Δb = Aᵀr with D the diagonal of AᵀA, lowers the damping d after a step that
// reduced the residual and raises it after one that did not (002 §2.4, last paragraph).
// The damping history is recorded on request.
//
// Before any iteration a design is checked: fewer samples than parameters, or normal equations
// whose condition number exceeds the limit, are refused with a status (never solved).
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace softsim::fit {

struct LmSettings {
  int max_iterations = 100;
  double function_tolerance = 1e-15;   // |Δcost| / cost
  double gradient_tolerance = 1e-12;   // max-norm of the gradient of the scaled problem
  double parameter_tolerance = 1e-14;  // |Δb| / (|b| + tol)
  double initial_damping = 1e-4;       // d at the first step (Ceres: 1 / initial trust-region radius)
  double max_condition = 1e12;         // refusal limit for cond(AᵀA)
  bool record_history = false;
};

enum class FitStatus { ok, too_few_samples, ill_conditioned, not_converged };

const char* to_string(FitStatus status);

struct LmIteration {
  int iteration = 0;
  double cost = 0.0;     // ½‖r‖² of the scaled problem after the iteration
  double damping = 0.0;  // d used for the next step (1 / trust-region radius)
  bool accepted = false;
};

struct LinearFit {
  FitStatus status = FitStatus::ok;
  std::string message;
  Eigen::VectorXd coefficients;
  double condition = 0.0;  // cond(AᵀA); +inf when AᵀA is singular
  int iterations = 0;
  double initial_cost = 0.0;  // ½‖y - A b0‖² in data units (b0 = 0)
  double final_cost = 0.0;    // ½‖y - A b‖² in data units
  std::string termination;
  std::vector<LmIteration> history;

  bool ok() const { return status == FitStatus::ok; }
};

// cond(AᵀA) = (σmax / σmin)² from the singular values of A; +inf when A is rank deficient.
double normal_equations_condition(const Eigen::MatrixXd& design);

// A design matrix checked once and shared by several right-hand sides (e.g. every load case
// of a surface fit, which all sample the same nodes).
class LinearDesign {
 public:
  LinearDesign(Eigen::MatrixXd design, const LmSettings& settings);

  FitStatus status() const { return status_; }
  const std::string& message() const { return message_; }
  double condition() const { return condition_; }
  int samples() const { return static_cast<int>(design_.rows()); }
  int parameters() const { return static_cast<int>(design_.cols()); }

  // Ceres LM from b0 = 0. A refused design returns its status without solving.
  LinearFit solve(const Eigen::VectorXd& y) const;

 private:
  Eigen::MatrixXd design_;
  LmSettings settings_;
  FitStatus status_ = FitStatus::ok;
  std::string message_;
  double condition_ = 0.0;
};

// One-shot convenience: check the design and solve.
LinearFit fit_linear(const Eigen::MatrixXd& design, const Eigen::VectorXd& y,
                     const LmSettings& settings);

// Throws NumericalError "<what>: <status>: <message>" unless the fit is ok.
const LinearFit& require_ok(const LinearFit& fit, const std::string& what);

}  // namespace softsim::fit
