#pragma once
// Error statistics of predicted surface displacements against a reference (RPIM cases or the
// exact superposition): RMSE, largest |error| and mean error per displacement component
// (002 Table 3), and the mean deviation of every node over a set of cases (002 Figs. 5–13).
#include <Eigen/Dense>

namespace softsim::fit {

struct ComponentErrors {
  Eigen::Vector3d rmse = Eigen::Vector3d::Zero();
  Eigen::Vector3d max_abs = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();  // signed mean of predicted − reference
  Eigen::Vector3d reference_rms = Eigen::Vector3d::Zero();  // RMS of the reference itself
  long samples = 0;  // nodes × cases per component
};

class ErrorAccumulator {
 public:
  explicit ErrorAccumulator(int nodes);
  // predicted: 3n values node-major; reference: nodes × 3. Adds one case.
  void add(const double* predicted, const Eigen::MatrixXd& reference);
  ComponentErrors result() const;
  // nodes × 3: mean of predicted − reference at each node over the cases added.
  Eigen::MatrixXd mean_deviation() const;

 private:
  int nodes_;
  int cases_ = 0;
  Eigen::Vector3d sum_sq_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d ref_sq_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d max_abs_ = Eigen::Vector3d::Zero();
  Eigen::MatrixXd deviation_sum_;
};

}  // namespace softsim::fit
