#include "softsim/multirate/block_integrator.hpp"

#include <cmath>
#include <set>
#include <sstream>

#include "softsim/io/errors.hpp"
#include "softsim/multirate/stability.hpp"

namespace softsim::multirate {

BlockIntegrator::BlockIntegrator(const ReducedSystem& system, int dof_begin, int dof_end, const SolverSpec& solver,
                                 double step, LinearSolverKind linear_solver, bool enforce_stability_limit,
                                 std::string name, SettingAtFault solver_setting)
    : name_(std::move(name)), begin_(dof_begin), end_(dof_end), step_(step), solver_(solver) {
  if (dof_begin < 0 || dof_end > system.num_dofs() || dof_end <= dof_begin)
    throw InputError(name_ + ": empty or out-of-range DOF block");
  if (!(step > 0) || !std::isfinite(step)) throw InputError(name_ + ": the time step must be positive");
  const int n = size();
  const double h = step;
  rows_ = system.stiffness.middleRows(begin_, n);
  rows_.makeCompressed();
  mass_ = system.mass.segment(begin_, n);
  const Eigen::VectorXd damping = system.damping.segment(begin_, n);
  rhs_.setZero(n);

  std::set<int> outside;
  for (int i = 0; i < n; ++i)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows_, i); it; ++it)
      if (it.col() < begin_ || it.col() >= end_) outside.insert(static_cast<int>(it.col()));
  connections_.assign(outside.begin(), outside.end());

  if (solver.kind == SolverKind::kExplicit) {
    stability_limit_ = explicit_step_limit(system, begin_, end_, solver.explicit_variant);
    if (enforce_stability_limit && h > stability_limit_) {
      std::ostringstream msg;
      msg << name_ << ": explicit step " << h << " s exceeds the stability limit " << stability_limit_
          << " s (001 eq. 4; " << (solver.explicit_variant == ExplicitVariant::kCentral ? "eq. 5" : "eq. 6")
          << " with omega_max <= " << omega_max_bound(system, begin_, end_) << " rad/s)";
      throw SetupError(solver_setting, msg.str());
    }
    // 001 eq. 5 (velocity form): (M + h/2 C) w+ = (M - h/2 C) w- + h r
    // 001 eq. 6:                 (M + h C)   w+ = M w- + h r
    const double c_new = solver.explicit_variant == ExplicitVariant::kCentral ? 0.5 * h : h;
    const double c_old = solver.explicit_variant == ExplicitVariant::kCentral ? -0.5 * h : 0.0;
    explicit_inverse_ = (mass_ + c_new * damping).cwiseInverse();
    explicit_keep_ = mass_ + c_old * damping;
    return;
  }

  Eigen::SparseMatrix<double> lhs = system.stiffness.block(begin_, begin_, n, n);
  if (solver.kind == SolverKind::kImplicit) {
    const bool newmark = solver.implicit_scheme == ImplicitScheme::kNewmark;
    const double a0 = newmark ? 4.0 / (h * h) : 1.0 / (h * h);  // mass coefficient
    const double a1 = newmark ? 2.0 / h : 1.0 / h;              // damping coefficient
    for (int i = 0; i < n; ++i) lhs.coeffRef(i, i) += a0 * mass_[i] + a1 * damping[i];
  }
  lhs.makeCompressed();
  solver_lhs_.factorize(lhs, linear_solver, name_);
}

void BlockIntegrator::residual(const Eigen::VectorXd& view, const Eigen::VectorXd& force,
                               const Eigen::VectorXd* previous_force) {
  // r = f_b - K_bb u_b - K_bo u_o (001 eq. 7 with the inactive values on the right-hand side)
  const int n = size();
  for (int i = 0; i < n; ++i) {
    double ku = 0.0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows_, i); it; ++it)
      ku += it.value() * view[it.col()];
    const double f = previous_force ? 0.5 * (force[begin_ + i] + (*previous_force)[begin_ + i]) : force[begin_ + i];
    rhs_[i] = f - ku;
  }
}

bool BlockIntegrator::advance(const Eigen::VectorXd& view, const Eigen::VectorXd& force,
                              const Eigen::VectorXd& previous_force, Eigen::VectorXd& u, Eigen::VectorXd& v) {
  const int n = size();
  const double h = step_;
  residual(view, force, solver_.kind == SolverKind::kExplicit ? &previous_force : nullptr);
  double check = 0.0;
  switch (solver_.kind) {
    case SolverKind::kStatic: {
      solver_lhs_.solve_in_place(rhs_);  // K_bb du = r
      for (int i = 0; i < n; ++i) {
        u[begin_ + i] += rhs_[i];
        v[begin_ + i] = 0.0;
        check += rhs_[i];
      }
      break;
    }
    case SolverKind::kImplicit: {
      if (solver_.implicit_scheme == ImplicitScheme::kNewmark) {
        // Average acceleration with the force constant over the step and the start acceleration
        // in equilibrium with it (M a = r - C v), i.e. the trapezoidal rule:
        //   (K + 4/h^2 M + 2/h C) du = 2 r + 4/h M v,   v+ = 2 du / h - v
        for (int i = 0; i < n; ++i) rhs_[i] = 2.0 * rhs_[i] + 4.0 / h * mass_[i] * v[begin_ + i];
        solver_lhs_.solve_in_place(rhs_);
        for (int i = 0; i < n; ++i) {
          const int d = begin_ + i;
          v[d] = 2.0 / h * rhs_[i] - v[d];
          u[d] += rhs_[i];
          check += rhs_[i];
        }
      } else {
        // Backward Euler: (K + M/h^2 + C/h) du = r + M v / h,   v+ = du / h
        for (int i = 0; i < n; ++i) rhs_[i] += mass_[i] * v[begin_ + i] / h;
        solver_lhs_.solve_in_place(rhs_);
        for (int i = 0; i < n; ++i) {
          const int d = begin_ + i;
          v[d] = rhs_[i] / h;
          u[d] += rhs_[i];
          check += rhs_[i];
        }
      }
      break;
    }
    case SolverKind::kExplicit: {
      for (int i = 0; i < n; ++i) {
        const int d = begin_ + i;
        const double w = (explicit_keep_[i] * v[d] + h * rhs_[i]) * explicit_inverse_[i];
        v[d] = w;
        u[d] += h * w;
        check += w;
      }
      break;
    }
  }
  return std::isfinite(check);
}

}  // namespace softsim::multirate
