#pragma once
// The exact baseline for a linear model: the response to any force at the loaded node is the
// superposition of the responses to unit forces along x, y and z.
#include <Eigen/Dense>

namespace softsim::fit {

class Superposition {
 public:
  // unit_solutions: 3n × 3, column d = response to a unit force along d, row 3 j + c.
  explicit Superposition(Eigen::MatrixXd unit_solutions);

  int node_count() const { return static_cast<int>(unit_.rows() / 3); }
  // Writes 3 * node_count() values, node-major, in m. No allocation.
  void apply(const Eigen::Vector3d& force, double* out) const;

 private:
  Eigen::MatrixXd unit_;
};

}  // namespace softsim::fit
