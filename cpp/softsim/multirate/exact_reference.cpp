#include "softsim/multirate/exact_reference.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/MatrixFunctions>

#include "softsim/io/errors.hpp"

namespace softsim::multirate {

ExactReference::ExactReference(const ReducedSystem& system, int contact_free_node, double frame_step)
    : dofs_per_node_(system.dofs_per_node),
      free_nodes_(system.num_free_nodes()),
      contact_dof_(contact_free_node * system.dofs_per_node) {
  const int n = system.num_dofs();
  const int p = dofs_per_node_;
  if (n > kMaxDofs)
    throw InputError("exact reference: " + std::to_string(n) + " free DOFs; the dense matrix exponential is limited to " +
                     std::to_string(kMaxDofs));
  if (contact_free_node < 0 || contact_free_node >= free_nodes_)
    throw InputError("exact reference: contact node is not a free node");
  if (!(frame_step > 0)) throw InputError("exact reference: the frame step must be positive");

  // Van Loan's block matrix [A B; 0 0] scaled by the frame length, in the balanced state
  // y = [u; tau v] (tau = 1 / omega_s, omega_s^2 = max K_ii / m_i) so that both off-diagonal
  // blocks of A have the size of the model's frequencies; the result is scaled back.
  const Eigen::MatrixXd k = Eigen::MatrixXd(system.stiffness);
  double omega_sq = 0.0;
  for (int i = 0; i < n; ++i) omega_sq = std::max(omega_sq, k(i, i) / system.mass[i]);
  const double tau = 1.0 / std::sqrt(omega_sq);
  Eigen::MatrixXd big = Eigen::MatrixXd::Zero(2 * n + p, 2 * n + p);
  big.block(0, n, n, n).diagonal().setConstant(1.0 / tau);
  for (int i = 0; i < n; ++i) {
    const double inv_m = 1.0 / system.mass[i];
    big.block(n + i, 0, 1, n) = -tau * inv_m * k.row(i);
    big(n + i, n + i) = -inv_m * system.damping[i];
  }
  for (int d = 0; d < p; ++d) big(n + contact_dof_ + d, 2 * n + d) = tau / system.mass[contact_dof_ + d];
  big *= frame_step;
  Eigen::MatrixXd e;
  {
    // Small dense products: Eigen's OpenMP-parallel GEMM only costs here (and varies with threads).
    const int threads = Eigen::nbThreads();
    Eigen::setNbThreads(1);
    e = big.exp();
    Eigen::setNbThreads(threads);
  }
  phi_ = e.topLeftCorner(2 * n, 2 * n);
  phi_.topRightCorner(n, n) *= tau;
  phi_.bottomLeftCorner(n, n) /= tau;
  gamma_ = e.block(0, 2 * n, 2 * n, p);
  gamma_.bottomRows(n) /= tau;
  if (!phi_.allFinite() || !gamma_.allFinite()) throw NumericalError("exact reference: matrix exponential is not finite");
  state_.setZero(2 * n);
  next_.setZero(2 * n);
}

void ExactReference::advance(const Eigen::VectorXd& contact_force) {
  next_.noalias() = phi_ * state_;
  next_.noalias() += gamma_ * contact_force;
  state_.swap(next_);
}

double ExactReference::loop_spectral_radius(double probe_stiffness) const {
  Eigen::MatrixXd loop = phi_;
  // f = k_s (p - u_c): the feedback subtracts k_s Gamma times the contact displacement.
  for (int d = 0; d < dofs_per_node_; ++d) loop.col(contact_dof_ + d) -= probe_stiffness * gamma_.col(d);
  const int threads = Eigen::nbThreads();
  Eigen::setNbThreads(1);
  const double radius = loop.eigenvalues().cwiseAbs().maxCoeff();
  Eigen::setNbThreads(threads);
  return radius;
}

}  // namespace softsim::multirate
