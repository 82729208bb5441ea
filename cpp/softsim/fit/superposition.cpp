#include "softsim/fit/superposition.hpp"

#include <stdexcept>

namespace softsim::fit {

Superposition::Superposition(Eigen::MatrixXd unit_solutions) : unit_(std::move(unit_solutions)) {
  if (unit_.cols() != 3 || unit_.rows() % 3 != 0)
    throw std::invalid_argument("Superposition: expected a 3n × 3 matrix of unit solutions");
}

void Superposition::apply(const Eigen::Vector3d& force, double* out) const {
  Eigen::Map<Eigen::VectorXd>(out, unit_.rows()).noalias() = unit_ * force;
}

}  // namespace softsim::fit
