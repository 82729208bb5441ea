#include "softsim/fit/relations.hpp"

#include <algorithm>
#include <cmath>

#include "softsim/io/errors.hpp"

namespace softsim::fit {

namespace {

void note_condition(CvScore& score, double condition) {
  if (!(condition <= score.max_condition)) score.max_condition = condition;  // keeps +inf
}

std::string fold_message(int f, const std::string& message) {
  return "fold " + std::to_string(f + 1) + ": " + message;
}

void throw_refused(const std::string& what, FitStatus status, const std::string& message) {
  throw NumericalError(what + ": " + to_string(status) + ": " + message);
}

// k-fold cross-validation, the same for the three relations: the rows of the design are the
// samples; each fold's training rows are solved for every column of Y (one right-hand side per
// column, e.g. one load case), and add_errors(f, test rows, coefficients B with one column per
// right-hand side, errors) books the fold's test errors. A failure refuses the score.
template <class AddErrors>
CvScore cross_validate(const FoldDesigns& folds, const Eigen::MatrixXd& Y, const std::string& too_few,
                       AddErrors&& add_errors) {
  CvScore score;
  score.parameters = folds.parameters();
  if (folds.samples() < 2) {
    refuse(score, FitStatus::too_few_samples, too_few);
    return score;
  }
  FoldErrors errors(folds.folds());
  Eigen::MatrixXd B(folds.parameters(), Y.cols());
  for (int f = 0; f < folds.folds(); ++f) {
    const LinearDesign& design = folds.design(f);
    note_condition(score, design.condition());
    if (design.status() != FitStatus::ok) {
      refuse(score, design.status(), fold_message(f, design.message()));
      return score;
    }
    for (Eigen::Index c = 0; c < Y.cols(); ++c) {
      const LinearFit fit = design.solve(Y(folds.train(f), c));
      if (!fit.ok()) {
        refuse(score, fit.status, fold_message(f, fit.message));
        return score;
      }
      B.col(c) = fit.coefficients;
    }
    add_errors(f, folds.test(f), B, errors);
  }
  errors.finish(score);
  return score;
}

FoldDesigns fold_designs(const Eigen::MatrixXd& design, const FitOptions& options) {
  return FoldDesigns(design, options.folds, options.seed, options.lm);
}

}  // namespace

AffineScale input_scale(const std::vector<double>& values, bool scale_inputs) {
  if (!scale_inputs || values.empty()) return AffineScale{};
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  return AffineScale::from_range(*lo, *hi);
}

double exact_floor_mse(const Eigen::MatrixXd& values, double exact_relative) {
  if (values.size() == 0) return 0.0;
  const double rms = std::sqrt(values.squaredNorm() / static_cast<double>(values.size()));
  return (exact_relative * rms) * (exact_relative * rms);
}

// ---------------- relation 1 ----------------

Eigen::MatrixXd polynomial_design(Basis basis, const AffineScale& scale, const std::vector<double>& x,
                                  int order) {
  if (order > kMaxOrder) throw std::invalid_argument("polynomial_design: order above kMaxOrder");
  Eigen::MatrixXd A(static_cast<Eigen::Index>(x.size()), order + 1);
  double phi[kMaxOrder + 1];
  for (std::size_t i = 0; i < x.size(); ++i) {
    evaluate_basis(basis, order, scale.to_unit(x[i]), phi);
    for (int m = 0; m <= order; ++m) A(static_cast<Eigen::Index>(i), m) = phi[m];
  }
  return A;
}

LinearFit fit_polynomial(const std::vector<double>& x, const std::vector<double>& y, int order,
                         const AffineScale& scale, const FitOptions& options) {
  const Eigen::Map<const Eigen::VectorXd> yv(y.data(), static_cast<Eigen::Index>(y.size()));
  return fit_linear(polynomial_design(options.basis, scale, x, order), yv, options.lm);
}

CvScore cv_polynomial(const std::vector<double>& x, const std::vector<double>& y, int order,
                      const AffineScale& scale, const FitOptions& options) {
  const Eigen::MatrixXd A = polynomial_design(options.basis, scale, x, order);
  const Eigen::Map<const Eigen::VectorXd> yv(y.data(), static_cast<Eigen::Index>(y.size()));
  return cross_validate(fold_designs(A, options), yv,
                        "cross-validation needs at least 2 samples, got " + std::to_string(x.size()),
                        [&](int f, const std::vector<int>& test, const Eigen::MatrixXd& B, FoldErrors& errors) {
                          for (int i : test) {
                            const double e = A.row(i).dot(B.col(0)) - yv[i];
                            errors.add(f, e * e);
                          }
                        });
}

namespace {
// What relations 2 and 3 report of one design solved for several right-hand sides.
FitSummary summarise(const LinearDesign& design, int max_iterations, const std::string& termination,
                     const Eigen::MatrixXd& residuals) {
  FitSummary summary;
  summary.condition = design.condition();
  summary.samples = design.samples();
  summary.parameters = design.parameters();
  summary.max_iterations = max_iterations;
  summary.termination = termination;
  const double n = static_cast<double>(residuals.size());
  summary.rmse = n > 0 ? std::sqrt(residuals.squaredNorm() / n) : 0.0;
  return summary;
}
}  // namespace

// ---------------- relation 2 ----------------

Eigen::MatrixXd fit_surfaces(const SurfaceTerms& terms, const SurfaceFrame& frame,
                             const Eigen::MatrixXd& xy, const Eigen::MatrixXd& values,
                             const FitOptions& options, const std::string& what, FitSummary* summary) {
  const Eigen::MatrixXd A = surface_design(terms, frame, xy);
  const LinearDesign design(A, options.lm);
  if (design.status() != FitStatus::ok) throw_refused(what, design.status(), design.message());
  Eigen::MatrixXd coefficients(terms.size(), values.cols());
  int max_iterations = 0;
  std::string termination;
  for (Eigen::Index c = 0; c < values.cols(); ++c) {
    const LinearFit fit = design.solve(values.col(c));
    require_ok(fit, what + ", case " + std::to_string(c + 1));
    coefficients.col(c) = fit.coefficients;
    max_iterations = std::max(max_iterations, fit.iterations);
    termination = fit.termination;
  }
  if (summary != nullptr)
    *summary = summarise(design, max_iterations, termination, A * coefficients - values);
  return coefficients;
}

SurfaceCv::SurfaceCv(const SurfaceTerms& terms, const SurfaceFrame& frame, const Eigen::MatrixXd& xy,
                     const FitOptions& options)
    : design_(surface_design(terms, frame, xy)), folds_(fold_designs(design_, options)) {}

CvScore SurfaceCv::score(const Eigen::MatrixXd& values) const {
  return cross_validate(folds_, values, "cross-validation needs at least 2 nodes",
                        [&](int f, const std::vector<int>& test, const Eigen::MatrixXd& B, FoldErrors& errors) {
                          const Eigen::MatrixXd A_test = design_(test, Eigen::all);
                          for (Eigen::Index c = 0; c < values.cols(); ++c) {
                            const Eigen::VectorXd e = A_test * B.col(c) - values(test, c);
                            for (Eigen::Index i = 0; i < e.size(); ++i) errors.add(f, e[i] * e[i]);
                          }
                        });
}

CvScore cv_surface(const SurfaceTerms& terms, const SurfaceFrame& frame, const Eigen::MatrixXd& xy,
                   const Eigen::MatrixXd& values, const FitOptions& options) {
  return SurfaceCv(terms, frame, xy, options).score(values);
}

// ---------------- relation 3 ----------------

Eigen::MatrixXd fit_parameter_relation(const std::vector<double>& delta, const AffineScale& delta_scale,
                                       const Eigen::MatrixXd& coefficients, int order,
                                       const FitOptions& options, const std::string& what,
                                       FitSummary* summary) {
  const Eigen::MatrixXd Phi = polynomial_design(options.basis, delta_scale, delta, order);
  const LinearDesign design(Phi, options.lm);
  if (design.status() != FitStatus::ok) throw_refused(what, design.status(), design.message());
  Eigen::MatrixXd beta(coefficients.rows(), order + 1);
  int max_iterations = 0;
  std::string termination;
  for (Eigen::Index k = 0; k < coefficients.rows(); ++k) {
    const LinearFit fit = design.solve(coefficients.row(k).transpose());
    require_ok(fit, what + ", coefficient p" + std::to_string(k + 1));
    beta.row(k) = fit.coefficients.transpose();
    max_iterations = std::max(max_iterations, fit.iterations);
    termination = fit.termination;
  }
  if (summary != nullptr)
    *summary = summarise(design, max_iterations, termination, beta * Phi.transpose() - coefficients);
  return beta;
}

CvScore cv_parameter_relation(const std::vector<double>& delta, const AffineScale& delta_scale,
                              const Eigen::MatrixXd& coefficients, const Eigen::MatrixXd& surface_design,
                              int order, const FitOptions& options) {
  const Eigen::MatrixXd Phi = polynomial_design(options.basis, delta_scale, delta, order);
  return cross_validate(fold_designs(Phi, options), coefficients.transpose(),
                        "cross-validation needs at least 2 load cases",
                        [&](int f, const std::vector<int>& test, const Eigen::MatrixXd& B, FoldErrors& errors) {
                          const Eigen::MatrixXd beta = B.transpose();
                          for (int i : test) {
                            // Against the case's own fitted surface: the misfit of relation 2, the
                            // same for every order of relation 3, would otherwise swamp the
                            // differences between those orders.
                            const Eigen::VectorXd dp = beta * Phi.row(i).transpose() - coefficients.col(i);
                            const Eigen::VectorXd e = surface_design * dp;
                            for (Eigen::Index r = 0; r < e.size(); ++r) errors.add(f, e[r] * e[r]);
                          }
                        });
}

}  // namespace softsim::fit
