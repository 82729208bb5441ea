#pragma once
// Fitting and cross-validating the three relations of 002 §3, one candidate order at a time.
//
//   relation 1 (002 eqs. 39–42): loaded-node displacement δ as a polynomial of a force component
//   relation 2 (002 eq. 44):     one displacement component over the surface nodes, per load case
//   relation 3 (002 eqs. 45–46): every surface coefficient as a polynomial of δ
//
// Every fit goes through Ceres Levenberg–Marquardt (lm_fit.hpp). The final fits throw
// NumericalError when refused or not converged; the cross-validation functions instead return a
// refused CvScore so that the CV table can show the row flagged.
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "softsim/fit/basis.hpp"
#include "softsim/fit/cross_validation.hpp"
#include "softsim/fit/lm_fit.hpp"
#include "softsim/fit/surface_basis.hpp"

namespace softsim::fit {

struct FitOptions {
  Basis basis = Basis::legendre;
  bool scale_inputs = true;  // map every input variable onto [-1, 1]
  LmSettings lm;
  int folds = 5;  // 0: leave-one-out
  std::uint64_t seed = 1;
  Selection selection = Selection::one_standard_error;
  // CV errors below (exact_relative × RMS of the data)² count as exact (see select_candidate).
  double exact_relative = 1e-9;
};

// The scale of an input variable: its range mapped onto [-1, 1], or the identity when inputs
// are not scaled.
AffineScale input_scale(const std::vector<double>& values, bool scale_inputs);

// Noise floor of select_candidate for data `values`.
double exact_floor_mse(const Eigen::MatrixXd& values, double exact_relative);

// ---------------- relation 1: y = p(x) ----------------
Eigen::MatrixXd polynomial_design(Basis basis, const AffineScale& scale, const std::vector<double>& x,
                                  int order);
LinearFit fit_polynomial(const std::vector<double>& x, const std::vector<double>& y, int order,
                         const AffineScale& scale, const FitOptions& options);
// k-fold over the samples.
CvScore cv_polynomial(const std::vector<double>& x, const std::vector<double>& y, int order,
                      const AffineScale& scale, const FitOptions& options);

// ---------------- relation 2: surfaces ----------------
struct FitSummary {
  double condition = 0.0;  // cond(AᵀA) of the design
  int samples = 0;
  int parameters = 0;
  int max_iterations = 0;  // over every right-hand side
  double rmse = 0.0;       // training residual (data units)
  std::string termination;
};

// values: nodes × cases (one displacement component of every case). Returns the coefficients
// (terms × cases). Throws NumericalError naming `what` when refused or not converged.
Eigen::MatrixXd fit_surfaces(const SurfaceTerms& terms, const SurfaceFrame& frame,
                             const Eigen::MatrixXd& xy, const Eigen::MatrixXd& values,
                             const FitOptions& options, const std::string& what,
                             FitSummary* summary = nullptr);
// k-fold over the nodes (the same held-out nodes for every case). The design over the nodes, its
// fold split and each fold's checked training design depend on the terms and the nodes only, not
// on the values: one SurfaceCv scores a candidate for every displacement component of every load
// direction sampled at the same nodes.
class SurfaceCv {
 public:
  SurfaceCv(const SurfaceTerms& terms, const SurfaceFrame& frame, const Eigen::MatrixXd& xy,
            const FitOptions& options);
  // values: nodes × cases.
  CvScore score(const Eigen::MatrixXd& values) const;

 private:
  Eigen::MatrixXd design_;
  FoldDesigns folds_;
};
// One candidate scored once: SurfaceCv(terms, frame, xy, options).score(values).
CvScore cv_surface(const SurfaceTerms& terms, const SurfaceFrame& frame, const Eigen::MatrixXd& xy,
                   const Eigen::MatrixXd& values, const FitOptions& options);

// ---------------- relation 3: surface coefficients as polynomials of δ ----------------
// coefficients: terms × cases (from fit_surfaces). Returns beta: terms × (order + 1).
Eigen::MatrixXd fit_parameter_relation(const std::vector<double>& delta, const AffineScale& delta_scale,
                                       const Eigen::MatrixXd& coefficients, int order,
                                       const FitOptions& options, const std::string& what,
                                       FitSummary* summary = nullptr);
// k-fold over the cases. A held-out case i is scored at every node by the surface difference
// its predicted coefficients make, surface_design · (p̂(δ_i) − p_i), where p_i are its own
// relation-2 coefficients: the error of relation 3 alone, in displacement units.
CvScore cv_parameter_relation(const std::vector<double>& delta, const AffineScale& delta_scale,
                              const Eigen::MatrixXd& coefficients, const Eigen::MatrixXd& surface_design,
                              int order, const FitOptions& options);

}  // namespace softsim::fit
