#pragma once
// The whole model solved at the haptic rate: every free DOF in one block, every frame. The
// baseline the asynchronous regions are compared with (001 §6 "whole solution").
#include <string>

#include "softsim/multirate/block_integrator.hpp"
#include "softsim/multirate/frame_stepper.hpp"

namespace softsim::multirate {

class WholeModel : public FrameStepper {
 public:
  // `contact_free_node` indexes the system's free nodes.
  WholeModel(const ReducedSystem& system, int contact_free_node, const SolverSpec& solver, double frame_step,
             LinearSolverKind linear_solver, bool enforce_stability_limit = true);

  void reset() override;
  void advance(const Eigen::VectorXd& contact_force) override;
  double contact_displacement(int d) const override { return u_[contact_dof_ + d]; }
  int dofs_per_node() const override { return dofs_per_node_; }
  int primary_nodes() const override { return free_nodes_; }
  const Eigen::VectorXd& displacement() const { return u_; }
  const BlockIntegrator& block() const { return block_; }

 private:
  int dofs_per_node_;
  int free_nodes_;
  int contact_dof_;
  BlockIntegrator block_;
  Eigen::VectorXd u_, v_, force_, previous_force_;
  long frame_ = 0;
};

}  // namespace softsim::multirate
