#pragma once
// One region's time step (001 §4 solvers applied as in 001 eq. 7): the rows of the DOF block
// [begin, end) are solved while every other DOF is held at the value the block sees, which
// moves the coupling K_bo u_o to the right-hand side:
//     static:    K_bb u_b = f_b - K_bo u_o
//     implicit:  (K_bb + a0 M_b + a1 C_b) du = f_b - K_b: u + inertia and damping terms
//     explicit:  per DOF, the lumped M and C make each row independent (001 eqs. 5-6).
// The whole model is the block that holds every DOF (nothing to move to the right-hand side).
// Everything constant (block rows of K, factorisation, per-DOF coefficients) is precomputed;
// advance() does not allocate.
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "softsim/multirate/linear_model.hpp"
#include "softsim/multirate/setup_error.hpp"
#include "softsim/multirate/solver_spec.hpp"
#include "softsim/multirate/spd_solver.hpp"

namespace softsim::multirate {

class BlockIntegrator {
 public:
  // `step` is this block's time step h (its update interval). An explicit block whose step is
  // above the stability limit throws SetupError blaming `solver_setting` (the setting that chose
  // its solver) when enforce_stability_limit is set.
  BlockIntegrator(const ReducedSystem& system, int dof_begin, int dof_end, const SolverSpec& solver,
                  double step, LinearSolverKind linear_solver, bool enforce_stability_limit, std::string name,
                  SettingAtFault solver_setting);

  int begin() const { return begin_; }
  int end() const { return end_; }
  int size() const { return end_ - begin_; }
  const std::string& name() const { return name_; }
  // DOFs outside the block that its rows couple to (001 §5 "connection nodes").
  const std::vector<int>& connections() const { return connections_; }
  // Largest stable step of an explicit block (infinity for static and implicit).
  double stability_limit() const { return stability_limit_; }

  // Advances the block by one step h. `view` holds the block's current displacement on
  // [begin, end) and, at connections(), what the block sees of its neighbours at the end of
  // the step; `force` is the external force per DOF, constant over the step (only the block's
  // rows are read). u and v (the velocity; the half-step velocity for explicit blocks, zero for
  // static ones) are updated on [begin, end). Returns false when the new displacement is not
  // finite. `previous_force` is the force of the step before (explicit blocks only: a force held
  // over each step acts on the half-step velocity with the mean of the two, which keeps the
  // central difference second order for the sampled haptic force and starts it correctly).
  bool advance(const Eigen::VectorXd& view, const Eigen::VectorXd& force, const Eigen::VectorXd& previous_force,
               Eigen::VectorXd& u, Eigen::VectorXd& v);

 private:
  void residual(const Eigen::VectorXd& view, const Eigen::VectorXd& force, const Eigen::VectorXd* previous_force);

  std::string name_;
  int begin_ = 0;
  int end_ = 0;
  double step_ = 0.0;
  SolverSpec solver_;
  double stability_limit_ = std::numeric_limits<double>::infinity();
  Eigen::SparseMatrix<double, Eigen::RowMajor> rows_;  // K restricted to the block's rows, all columns
  std::vector<int> connections_;
  Eigen::VectorXd mass_;
  // Explicit: du = h * w, w = (explicit_keep_ .* v + h r) .* explicit_inverse_.
  Eigen::VectorXd explicit_keep_, explicit_inverse_;
  SpdSolver solver_lhs_;
  Eigen::VectorXd rhs_;  // scratch of the block size
};

}  // namespace softsim::multirate
