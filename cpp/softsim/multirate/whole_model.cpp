#include "softsim/multirate/whole_model.hpp"

#include <string>

#include "softsim/io/errors.hpp"

namespace softsim::multirate {

WholeModel::WholeModel(const ReducedSystem& system, int contact_free_node, const SolverSpec& solver,
                       double frame_step, LinearSolverKind linear_solver, bool enforce_stability_limit)
    : dofs_per_node_(system.dofs_per_node),
      free_nodes_(system.num_free_nodes()),
      contact_dof_(contact_free_node * system.dofs_per_node),
      block_(system, 0, system.num_dofs(), solver, frame_step, linear_solver, enforce_stability_limit,
             "whole model", {SettingAtFault::Kind::kWholeSolver}) {
  if (contact_free_node < 0 || contact_free_node >= free_nodes_)
    throw InputError("whole model: contact node is not a free node");
  reset();
}

void WholeModel::reset() {
  const int n = block_.size();
  u_.setZero(n);
  v_.setZero(n);
  force_.setZero(n);
  previous_force_.setZero(n);
  frame_ = 0;
}

void WholeModel::advance(const Eigen::VectorXd& contact_force) {
  previous_force_.segment(contact_dof_, dofs_per_node_) = force_.segment(contact_dof_, dofs_per_node_);
  force_.segment(contact_dof_, dofs_per_node_) = contact_force;
  ++frame_;
  if (!block_.advance(u_, force_, previous_force_, u_, v_))
    throw NumericalError("whole model: non-finite displacement at frame " + std::to_string(frame_));
}

}  // namespace softsim::multirate
