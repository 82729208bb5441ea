#include "softsim/fit/lm_fit.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include <ceres/ceres.h>

#include "softsim/io/errors.hpp"

namespace softsim::fit {

const char* to_string(FitStatus status) {
  switch (status) {
    case FitStatus::ok: return "ok";
    case FitStatus::too_few_samples: return "too_few_samples";
    case FitStatus::ill_conditioned: return "ill_conditioned";
    case FitStatus::not_converged: return "not_converged";
  }
  return "unknown";
}

double normal_equations_condition(const Eigen::MatrixXd& design) {
  if (design.cols() == 0) return 1.0;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(design);
  const Eigen::VectorXd& s = svd.singularValues();
  const double smax = s(0);
  const double smin = s(s.size() - 1);
  if (!(smin > 0.0) || !(smax > 0.0)) return std::numeric_limits<double>::infinity();
  const double ratio = smax / smin;
  return ratio * ratio;
}

namespace {

std::string format(double v) {
  std::ostringstream os;
  os.precision(3);
  os << v;
  return os.str();
}

// r(b) = A b - y (y already divided by its scale); the Jacobian is A itself.
class LinearResidual final : public ceres::CostFunction {
 public:
  LinearResidual(const Eigen::MatrixXd& design, const Eigen::VectorXd& y) : design_(design), y_(y) {
    set_num_residuals(static_cast<int>(design.rows()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(design.cols()));
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Eigen::Map<const Eigen::VectorXd> b(parameters[0], design_.cols());
    Eigen::Map<Eigen::VectorXd>(residuals, design_.rows()).noalias() = design_ * b - y_;
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          jacobians[0], design_.rows(), design_.cols()) = design_;
    }
    return true;
  }

 private:
  const Eigen::MatrixXd& design_;
  const Eigen::VectorXd& y_;
};

class HistoryRecorder final : public ceres::IterationCallback {
 public:
  explicit HistoryRecorder(std::vector<LmIteration>& out) : out_(out) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    LmIteration it;
    it.iteration = s.iteration;
    it.cost = s.cost;
    it.damping = s.trust_region_radius > 0.0 ? 1.0 / s.trust_region_radius : 0.0;
    it.accepted = s.step_is_successful;
    out_.push_back(it);
    return ceres::SOLVER_CONTINUE;
  }

 private:
  std::vector<LmIteration>& out_;
};

}  // namespace

LinearDesign::LinearDesign(Eigen::MatrixXd design, const LmSettings& settings)
    : design_(std::move(design)), settings_(settings) {
  if (design_.rows() < design_.cols() || design_.cols() == 0) {
    status_ = FitStatus::too_few_samples;
    message_ = std::to_string(design_.rows()) + " samples for " + std::to_string(design_.cols()) +
               " parameters";
    condition_ = std::numeric_limits<double>::infinity();
    return;
  }
  condition_ = normal_equations_condition(design_);
  if (!(condition_ <= settings_.max_condition)) {
    status_ = FitStatus::ill_conditioned;
    message_ = "cond(AᵀA) = " + (std::isfinite(condition_) ? format(condition_) : std::string("inf")) +
               " exceeds the limit " + format(settings_.max_condition);
  }
}

LinearFit LinearDesign::solve(const Eigen::VectorXd& y) const {
  LinearFit fit;
  fit.condition = condition_;
  fit.status = status_;
  fit.message = message_;
  if (status_ != FitStatus::ok) return fit;

  // Residuals of order one make the absolute gradient tolerance meaningful for any data unit.
  const double y_max = y.size() > 0 ? y.cwiseAbs().maxCoeff() : 0.0;
  const double y_scale = y_max > 0.0 ? y_max : 1.0;
  const Eigen::VectorXd y_scaled = y / y_scale;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(design_.cols());

  LinearResidual residual(design_, y_scaled);
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  problem.AddResidualBlock(&residual, nullptr, b.data());

  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;  // 002 eqs. 33–37
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = settings_.max_iterations;
  options.function_tolerance = settings_.function_tolerance;
  options.gradient_tolerance = settings_.gradient_tolerance;
  options.parameter_tolerance = settings_.parameter_tolerance;
  options.initial_trust_region_radius = 1.0 / settings_.initial_damping;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  HistoryRecorder recorder(fit.history);
  if (settings_.record_history) options.callbacks.push_back(&recorder);

  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  fit.iterations = static_cast<int>(summary.iterations.size()) - 1;
  fit.termination = ceres::TerminationTypeToString(summary.termination_type);
  fit.coefficients = b * y_scale;
  fit.initial_cost = summary.initial_cost * y_scale * y_scale;
  fit.final_cost = summary.final_cost * y_scale * y_scale;
  if (summary.termination_type != ceres::CONVERGENCE || !fit.coefficients.allFinite()) {
    fit.status = FitStatus::not_converged;
    fit.message = "Levenberg–Marquardt stopped with " + fit.termination + " after " +
                  std::to_string(fit.iterations) + " iterations (limit " +
                  std::to_string(settings_.max_iterations) + "): " + summary.message;
  }
  return fit;
}

LinearFit fit_linear(const Eigen::MatrixXd& design, const Eigen::VectorXd& y,
                     const LmSettings& settings) {
  return LinearDesign(design, settings).solve(y);
}

const LinearFit& require_ok(const LinearFit& fit, const std::string& what) {
  if (!fit.ok()) throw NumericalError(what + ": " + to_string(fit.status) + ": " + fit.message);
  return fit;
}

}  // namespace softsim::fit
