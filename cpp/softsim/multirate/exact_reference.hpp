#pragma once
// The exact solution of the discrete (finite element) linear system over one haptic frame,
// used as the reference of 001 §6 ("analytical solution"): not another time stepper.
//
// With x = [u; v], M u'' + C u' + K u = E f is x' = A x + B f, A = [0 I; -M^-1 K  -M^-1 C],
// B = [0; M^-1 E]. The haptic loop holds the spring force constant over a frame, so over a
// frame of length T the solution is exactly
//     x(t + T) = Phi x(t) + Gamma f,   Phi = exp(A T),   Gamma = int_0^T exp(A s) ds B,
// both read off one matrix exponential (Van Loan): exp([A B; 0 0] T) = [Phi Gamma; 0 I].
// Dense: meant for the small models of the 1-D experiments (at most kMaxDofs free DOFs).
#include <Eigen/Core>

#include "softsim/multirate/frame_stepper.hpp"
#include "softsim/multirate/linear_model.hpp"

namespace softsim::multirate {

class ExactReference : public FrameStepper {
 public:
  static constexpr int kMaxDofs = 2000;

  // Throws InputError above kMaxDofs free DOFs.
  ExactReference(const ReducedSystem& system, int contact_free_node, double frame_step);

  void reset() override { state_.setZero(); }
  void advance(const Eigen::VectorXd& contact_force) override;
  double contact_displacement(int d) const override { return state_[contact_dof_ + d]; }
  int dofs_per_node() const override { return dofs_per_node_; }
  int primary_nodes() const override { return free_nodes_; }

  const Eigen::VectorXd& state() const { return state_; }     // [u; v]
  // Spectral radius of the closed haptic loop x+ = (Phi - k_s Gamma E^T [I 0]) x: below 1 the
  // probe spring of stiffness k_s coupled once per frame is stable on the exact model.
  double loop_spectral_radius(double probe_stiffness) const;

 private:
  int dofs_per_node_;
  int free_nodes_;
  int contact_dof_;
  Eigen::MatrixXd phi_, gamma_;  // Phi, Gamma (2n x dofs_per_node)
  Eigen::VectorXd state_, next_;
};

}  // namespace softsim::multirate
