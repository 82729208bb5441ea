#include "softsim/dynamics/explicit_solver.hpp"

namespace softsim::dynamics {

// Gather (into f, the internal force on node i) and central-difference update (000 eq. 33) of
// node i; `check` turns NaN as soon as a value is not finite.
template <bool kGravity, bool kApplied>
inline void ExplicitSolver::update_node(int i, const double* up, const double* uc, double* un, double& check,
                                        double f[3], const Eigen::Vector3d& g) const {
  elements_.gather(i, f);
  const double a = A_[i], b = B_[i], c = C_[i];
  double x = b * uc[3 * i] - c * up[3 * i] - a * f[0];
  double y = b * uc[3 * i + 1] - c * up[3 * i + 1] - a * f[1];
  double z = b * uc[3 * i + 2] - c * up[3 * i + 2] - a * f[2];
  if (kGravity) {
    const double am = Am_[i];
    x += am * g.x();
    y += am * g.y();
    z += am * g.z();
  }
  if (kApplied) {  // + A F as a nodal load enters; constrained components are overwritten later
    x += a * applied_force_[3 * i];
    y += a * applied_force_[3 * i + 1];
    z += a * applied_force_[3 * i + 2];
  }
  un[3 * i] = x;
  un[3 * i + 1] = y;
  un[3 * i + 2] = z;
  check += (x - x) + (y - y) + (z - z);
}

// Nodes list[begin, split) are plain, list[split, end) special.
template <bool kGravity, bool kApplied>
void ExplicitSolver::update_nodes(const int* list, int begin, int split, int end, int step, const double* up,
                                  const double* uc, double* un, double& check, const Eigen::Vector3d& g) {
  for (int k = begin; k < split; ++k) {
    double f[3];
    update_node<kGravity, kApplied>(list[k], up, uc, un, check, f, g);
  }
  for (int k = split; k < end; ++k) {
    // A held node's eq. 33 value would be overwritten by its constraints: skip the gather and
    // the update (its internal force is only needed for a moving constraint, never held).
    double f[3] = {0.0, 0.0, 0.0};
    if (!held_[list[k]]) update_node<kGravity, kApplied>(list[k], up, uc, un, check, f, g);
    update_special(list[k], step, f, up, uc, un);
  }
}

void ExplicitSolver::update_nodes(const int* list, int begin, int split, int end, int step, const double* up,
                                  const double* uc, double* un, double& check, const Eigen::Vector3d& g) {
  const bool applied = !applied_.empty();
  if (gravity_) {
    if (applied) update_nodes<true, true>(list, begin, split, end, step, up, uc, un, check, g);
    else update_nodes<true, false>(list, begin, split, end, step, up, uc, un, check, g);
  } else {
    if (applied) update_nodes<false, true>(list, begin, split, end, step, up, uc, un, check, g);
    else update_nodes<false, false>(list, begin, split, end, step, up, uc, un, check, g);
  }
}

Eigen::Vector3d ExplicitSolver::gravity_at(int step) const {
  if (!gravity_ramped_) return scene_.gravity;
  return scene_.gravity_ramp.at(time_at(step)) * scene_.gravity;
}

double ExplicitSolver::gravity_potential(const double* u) const {
  double p = 0;
  for (int i = 0; i < n_; ++i)
    for (int k = 0; k < 3; ++k) p += mass_[i] * scene_.gravity[k] * u[3 * i + k];
  return p;
}

// The work of ramped gravity on [t_{s−1}, t_s], booked at step s while
// the ramp runs (u_s = uc; 000 eq. 33's loads R enter the energy balance trapezoidally); one pass over
// the nodes per step, only then.
void ExplicitSolver::book_gravity_work(int step, const double* uc) {
  if (!gravity_ramped_ || step < 1) return;
  const double t_before = time_at(step - 1);
  if (!(t_before < scene_.gravity_ramp.duration)) return;
  const double r_mean = 0.5 * (scene_.gravity_ramp.at(t_before) + scene_.gravity_ramp.at(time_at(step)));
  const double p = gravity_potential(uc);
  gravity_ramp_work_ += r_mean * (p - gravity_booked_potential_);
  gravity_booked_potential_ = p;
}

// Loads, probe, constraints, work booking and trajectory samples of node i, after its update;
// `f` is the internal force on node i that the update gathered.
void ExplicitSolver::update_special(int i, int step, const double f[3], const double* up, const double* uc,
                                    double* un) {
  // t = t_step; the steps before and after it (equal but at a step-size transition).
  const StepSegment& seg = segments_.back();
  const double t = seg.time + (step - seg.first_step) * seg.dt;
  const double dt = seg.dt;
  const double dt_before = transition_ && step == seg.first_step ? step_size(step - 1) : dt;
  // Nodal loads: R enters eq. 33 as + A R. External work is booked on [t − Δt, t] with the
  // trapezoidal rule, ½ (R(t − Δt) + R(t)) · (u(t) − u(t − Δt)), the form the central-difference
  // energy balance takes.
  for (int e = load_begin_[i]; e < load_begin_[i + 1]; ++e) {
    const LoadEntry& le = loads_[e];
    const NodalLoad& load = scene_.loads[le.load];
    const double r = load.ramp.at(t);
    for (int k = 0; k < 3; ++k)
      if (le.free[k]) un[3 * i + k] += A_[i] * r * load.force_per_node[k];
    if (step > 0) {
      const double r_mean = 0.5 * (load.ramp.at(t - dt_before) + r);
      double w = 0;
      for (int k = 0; k < 3; ++k)
        if (le.free[k]) w += r_mean * load.force_per_node[k] * (uc[3 * i + k] - up[3 * i + k]);
      load_work_[e] += w;
    }
  }
  // The probe spring pulls its node towards the tool tip.
  const bool probe_here = scene_.has_probe && scene_.probe.node == i;
  Eigen::Vector3d probe_force = Eigen::Vector3d::Zero();
  if (probe_here) {
    const Eigen::Vector3d ui(uc[3 * i], uc[3 * i + 1], uc[3 * i + 2]);
    probe_force = scene_.probe.stiffness * (scene_.probe.tip_displacement(t) - ui);
    for (int k = 0; k < 3; ++k)
      if (probe_free_[k]) un[3 * i + k] += A_[i] * probe_force[k];
    if (probe_force_ && step % opt_.trajectory_interval == 0)
      (*probe_force_)[step / opt_.trajectory_interval] = probe_force;
  }
  // Constraints overwrite; their work is booked like the loads', and a moving constraint's force
  // is the one that produces its motion, M a + D v + F.
  const double alpha = opt_.damping_alpha;
  for (int e = dof_begin_[i]; e < dof_begin_[i + 1]; ++e) {
    const ConstrainedDof& d = dofs_[e];
    const int q = 3 * i + d.component;
    const double value = d.value * scene_.constraints[d.constraint].ramp.at(t + dt);
    if (moving_[d.constraint]) {
      const double m = mass_[i];
      double total;
      if (dt_before == dt) {
        total = m * (value - 2.0 * uc[q] + up[q]) / (dt * dt) + alpha * m * (value - up[q]) / (2.0 * dt) + f[d.component];
      } else {  // the variable-step form (central_difference.hpp)
        const double v_after = (value - uc[q]) / dt, v_before = (uc[q] - up[q]) / dt_before;
        total = m * (v_after - v_before) / (0.5 * (dt + dt_before)) + alpha * m * 0.5 * (v_after + v_before) + f[d.component];
      }
      if (step > 0) dof_work_[e] += 0.5 * (dof_force_[e] + total) * (uc[q] - up[q]);
      dof_force_[e] = total;
    }
    un[q] = value;
  }
  if (probe_here) {
    if (step > 0)
      for (int k = 0; k < 3; ++k)
        if (probe_free_[k]) probe_work_ += 0.5 * (probe_previous_[k] + probe_force[k]) * (uc[3 * i + k] - up[3 * i + k]);
    probe_previous_ = probe_force;
  }
  sample_trajectories(i, step, un);
}

void ExplicitSolver::sample_trajectories(int i, int step, const double* un) {
  if (trajectories_ && (step + 1) % opt_.trajectory_interval == 0) {
    const int sample = (step + 1) / opt_.trajectory_interval;
    for (int j = trajectory_begin_[i]; j < trajectory_begin_[i + 1]; ++j)
      (*trajectories_)[trajectory_order_[j]][sample] = Eigen::Vector3d(un[3 * i], un[3 * i + 1], un[3 * i + 2]);
  }
}

}  // namespace softsim::dynamics
