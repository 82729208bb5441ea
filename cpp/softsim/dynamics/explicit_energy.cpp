#include "softsim/dynamics/explicit_solver.hpp"

#include <algorithm>

#include "softsim/dynamics/parallel.hpp"

namespace softsim::dynamics {

using detail::parallel;

double ExplicitSolver::external_work(const double* u_mid) const {
  double w = probe_work_ + applied_work_;
  for (std::size_t a = 0; a < applied_.size(); ++a)
    for (int k = 0; k < 3; ++k) {
      const int q = 3 * applied_[a].node + k;
      if (!constrained_[q]) w += applied_[a].force[k] * (u_mid[q] - applied_from_[3 * a + k]);
    }
  for (double x : dof_work_) w += x;
  for (double x : load_work_) w += x;
  for (double x : contact_work_) w += x;
  return w;
}

EnergySample ExplicitSolver::sample_energy(int n_done, const double* u_before, const double* u_mid,
                                           const double* u_after, double& bound_kinetic, double& min_j,
                                           int& min_j_element) {
  // Time t_{n−1}, strain energy at u_{n−1}. The kinetic energy is the one the central-difference
  // scheme conserves exactly for a linear undamped system: ½ v⁻·M v⁺ with the half-step
  // velocities around t_{n−1}; `bound_kinetic` = ½ (|v⁻|²_M + |v⁺|²_M)/2 ≥ 0 for the growth check.
  // The steps before and after t_{n−1} (equal unless the step was re-estimated in between).
  const double dt_before = step_size(n_done - 2), dt_after = step_size(n_done - 1);
  EnergySample s;
  s.time = time_at(n_done - 1);
  double kinetic = 0, bound = 0, gravity_work = 0;
  for (int i = 0; i < n_; ++i)
    for (int k = 0; k < 3; ++k) {
      const int q = 3 * i + k;
      const double vm = (u_mid[q] - u_before[q]) / dt_before, vp = (u_after[q] - u_mid[q]) / dt_after;
      kinetic += 0.5 * mass_[i] * vm * vp;
      bound += 0.25 * mass_[i] * (vm * vm + vp * vp);
      gravity_work += mass_[i] * scene_.gravity[k] * u_mid[q];
    }
  bound_kinetic = bound;
  std::fill(part_min_j_.begin(), part_min_j_.end(), 1e300);
  std::fill(part_min_j_element_.begin(), part_min_j_element_.end(), -1);
  parallel(opt_.threads, [&](int tid, int nthreads) {
    for (int p = tid; p < opt_.threads; p += nthreads)
      elements_.energies(u_mid, element_ranges_[p], element_ranges_[p + 1], slot_energy_.data(),
                         slot_volume_ratio_.data(), part_min_j_[p], part_min_j_element_[p]);
  });
  for (int p = 0; p < opt_.threads; ++p)
    if (part_min_j_[p] < min_j) {
      min_j = part_min_j_[p];
      min_j_element = part_min_j_element_[p];
    }
  double strain = 0;
  for (double e : slot_energy_) strain += e;
  strain += elements_.nodal_volumetric_energy(slot_volume_ratio_.data());
  s.kinetic = kinetic;
  s.strain = strain;
  // Constant gravity: its work is G·u exactly (the booked terms stay 0).
  s.external_work = external_work(u_mid) + (gravity_ramp_work_ + (gravity_work - gravity_booked_potential_));
  return s;
}

}  // namespace softsim::dynamics
