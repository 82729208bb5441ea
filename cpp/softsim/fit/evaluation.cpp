#include "softsim/fit/evaluation.hpp"

#include <algorithm>
#include <cmath>

namespace softsim::fit {

ErrorAccumulator::ErrorAccumulator(int nodes) : nodes_(nodes), deviation_sum_(Eigen::MatrixXd::Zero(nodes, 3)) {}

void ErrorAccumulator::add(const double* predicted, const Eigen::MatrixXd& reference) {
  for (int j = 0; j < nodes_; ++j)
    for (int c = 0; c < 3; ++c) {
      const double e = predicted[3 * j + c] - reference(j, c);
      sum_sq_[c] += e * e;
      sum_[c] += e;
      ref_sq_[c] += reference(j, c) * reference(j, c);
      max_abs_[c] = std::max(max_abs_[c], std::abs(e));
      deviation_sum_(j, c) += e;
    }
  ++cases_;
}

ComponentErrors ErrorAccumulator::result() const {
  ComponentErrors r;
  r.samples = static_cast<long>(nodes_) * cases_;
  if (r.samples == 0) return r;
  const double n = static_cast<double>(r.samples);
  for (int c = 0; c < 3; ++c) {
    r.rmse[c] = std::sqrt(sum_sq_[c] / n);
    r.mean[c] = sum_[c] / n;
    r.reference_rms[c] = std::sqrt(ref_sq_[c] / n);
  }
  r.max_abs = max_abs_;
  return r;
}

Eigen::MatrixXd ErrorAccumulator::mean_deviation() const {
  if (cases_ == 0) return deviation_sum_;
  return deviation_sum_ / static_cast<double>(cases_);
}

}  // namespace softsim::fit
