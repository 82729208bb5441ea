#include "softsim/dynamics/explicit_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "softsim/dynamics/central_difference.hpp"
#include "softsim/dynamics/parallel.hpp"
#include "softsim/io/errors.hpp"

namespace softsim::dynamics {

using detail::barrier;
using detail::parallel;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

constexpr int kTimingStride = 8;

// The smallest J = det F over the whole set at u, and the (original) element it belongs to: a
// full energy pass, for failure messages only.
struct MinJ {
  double j = 1e300;
  int element = -1;
};

MinJ min_j_element(const fem::ElementSet& elements, const double* u) {
  MinJ m;
  std::vector<double> energy(elements.padded_size()), volume_ratio(elements.padded_size());
  elements.energies(u, 0, elements.padded_size(), energy.data(), volume_ratio.data(), m.j, m.element);
  return m;
}

}  // namespace

ExplicitSolver::ExplicitSolver(fem::ElementSet& elements, std::vector<double> masses, const Scene& scene,
                               const ExplicitOptions& options)
    : elements_(elements), mass_(std::move(masses)), scene_(scene), opt_(options), n_(elements.num_nodes()) {
  if (static_cast<int>(mass_.size()) != n_) throw std::invalid_argument("ExplicitSolver: one mass per node");
  if (!(opt_.dt > 0)) throw InputError("solver: the time step must be positive");
  if (opt_.steps < 0) throw InputError("solver: the step count must not be negative");
  if (opt_.damping_alpha < 0) throw InputError("damping: alpha must not be negative");
  if (opt_.threads < 1) throw InputError("threads: at least one thread is required");
  opt_.energy_interval = std::max(opt_.energy_interval, 1);
  opt_.trajectory_interval = std::max(opt_.trajectory_interval, 1);
  for (int node : opt_.trajectory_nodes)
    if (node < 0 || node >= n_) throw InputError("output: trajectory node " + std::to_string(node) + " out of range");
  if (opt_.adapt_step) {
    if (!opt_.critical_step) throw std::invalid_argument("ExplicitSolver: adapt_step needs critical_step");
    if (!(opt_.step_safety > 0 && opt_.step_safety <= 1.0))
      throw InputError("solver: the safety factor must lie in (0, 1]");
    opt_.step_check_interval = std::max(opt_.step_check_interval, 1);
  }

  A_.resize(n_);
  B_.resize(n_);
  C_.resize(n_);
  Am_.resize(n_);
  set_coefficients(opt_.dt, opt_.dt);
  gravity_ = scene_.gravity.squaredNorm() > 0;
  gravity_ramped_ = gravity_ && scene_.gravity_ramp.duration > 0;

  dofs_ = resolve_constraints(scene_, n_);
  const std::vector<char> mask = constrained_mask(dofs_, n_);
  constrained_ = mask;
  moving_.assign(scene_.constraints.size(), 0);  // set by start()
  for (std::size_t l = 0; l < scene_.loads.size(); ++l)
    for (int node : scene_.loads[l].nodes) {
      if (node < 0 || node >= n_) throw InputError("load \"" + scene_.loads[l].name + "\": node out of range");
      LoadEntry e{node, static_cast<int>(l), {}};
      for (int k = 0; k < 3; ++k) e.free[k] = !mask[3 * node + k];
      loads_.push_back(e);
    }
  std::stable_sort(loads_.begin(), loads_.end(), [](const LoadEntry& a, const LoadEntry& b) { return a.node < b.node; });
  if (scene_.has_probe) {
    if (scene_.probe.node < 0 || scene_.probe.node >= n_) throw InputError("probe: node out of range");
    for (int k = 0; k < 3; ++k) probe_free_[k] = !mask[3 * scene_.probe.node + k];
  }

  build_contacts(mask);
  element_ranges_ = elements_.balanced_ranges(opt_.threads);
  initial_scene_ = scene_;
  double total_mass = 0;
  for (double m : mass_) total_mass += m;
  const double total_volume = total_mass / elements_.material().elastic.density;
  energy_floor_ = 1e-12 * elements_.material().elastic.youngs_modulus * total_volume;
  slot_energy_.assign(elements_.padded_size(), 0.0);
  slot_volume_ratio_.assign(elements_.padded_size(), 1.0);
  part_min_j_.assign(opt_.threads, 1e300);
  part_min_j_element_.assign(opt_.threads, -1);
  build_schedule();
}

void ExplicitSolver::set_initial_state(std::vector<double> u0, std::vector<double> v0) {
  if (!u0.empty() && static_cast<int>(u0.size()) != 3 * n_) throw std::invalid_argument("initial displacement size");
  if (!v0.empty() && static_cast<int>(v0.size()) != 3 * n_) throw std::invalid_argument("initial velocity size");
  u0_ = std::move(u0);
  v0_ = std::move(v0);
  u_before_.clear();
}

void ExplicitSolver::set_resumed_state(std::vector<double> u_now, std::vector<double> u_before) {
  if (static_cast<int>(u_now.size()) != 3 * n_ || u_before.size() != u_now.size())
    throw std::invalid_argument("resumed state size");
  v0_.resize(u_now.size());
  for (std::size_t q = 0; q < u_now.size(); ++q) v0_[q] = (u_now[q] - u_before[q]) / opt_.dt;
  u0_ = std::move(u_now);
  u_before_ = std::move(u_before);
}

// The central-difference coefficients of 000 eq. 33 for a step of `dt_after` after one of
// `dt_before` (the constant-step ones when equal).
void ExplicitSolver::set_coefficients(double dt_before, double dt_after) {
  coefficient_dt_before_ = dt_before;
  coefficient_dt_after_ = dt_after;
  for (int i = 0; i < n_; ++i) set_node_coefficients(i);
}

// A node without mass (none of its elements is left after a cut) holds its place: u_{n+1} = u_n.
void ExplicitSolver::set_node_coefficients(int i) {
  if (!(mass_[i] > 0)) {
    A_[i] = C_[i] = Am_[i] = 0.0;
    B_[i] = 1.0;
    return;
  }
  const CentralDifference cd = central_difference(mass_[i], opt_.damping_alpha, coefficient_dt_before_, coefficient_dt_after_);
  A_[i] = cd.A;
  B_[i] = cd.B;
  C_[i] = cd.C;
  Am_[i] = cd.A * mass_[i];
}

// The step segment that step `step` lies in (the first one for steps before it, the current one
// beyond the last); before any reset, one segment of the configured step.
StepSegment ExplicitSolver::segment_at(int step) const {
  if (segments_.empty()) return StepSegment{0, 0.0, opt_.dt};
  auto it = segments_.rbegin();
  while (it + 1 != segments_.rend() && it->first_step > step) ++it;
  return *it;
}

double ExplicitSolver::time_at(int step) const {
  const StepSegment seg = segment_at(step);
  // With one segment (a constant step) this is step × dt exactly.
  return seg.time + (step - seg.first_step) * seg.dt;
}

double ExplicitSolver::step_size(int step) const { return segment_at(step).dt; }

std::string ExplicitSolver::where(int step) const {
  std::ostringstream s;
  s << "explicit step " << step << " (t = " << time_at(step) << " s)";
  return s.str();
}

// A failure at `step` whose step size exceeds the critical step of `u` (the last sound state) is
// a step-size failure and is reported as one; otherwise `what` is reported as it is.
void ExplicitSolver::fail_step_size(int step, const double* u, const std::string& what) const {
  const double dt = step_size(step);
  if (opt_.critical_step) {
    const double critical = opt_.critical_step(u);
    if (dt > critical) {
      std::ostringstream msg;
      msg << where(step) << ": step-size failure: the step " << dt << " s exceeds the critical step " << critical
          << " s of the deformed mesh (000 eq. 34 on the current geometry)"
          << (opt_.adapt_step ? ", which shrank faster than it was re-estimated (every " +
                                    std::to_string(opt_.step_check_interval) + " steps)"
                              : "")
          << "; lower solver.safety_factor (or solver.dt). It showed as: " << what;
      throw NumericalError(msg.str());
    }
  }
  throw NumericalError(where(step) + ": " + what);
}

void ExplicitSolver::fail_inversion(int step, double J, int e) const {
  std::ostringstream msg;
  msg << where(step) << ": element " << e << " (" << fem::kind_name(elements_.kinds()[e])
      << ") is inverted: J = " << J << " <= 0";
  throw NumericalError(msg.str());
}

void ExplicitSolver::reset() {
  started_ = false;
  start();
}

void ExplicitSolver::start() {
  const int n3 = 3 * n_;
  const double dt = opt_.dt;
  if (segments_.size() > 1 || transition_) set_coefficients(dt, dt);
  segments_.assign(1, StepSegment{0, 0.0, dt});
  transition_ = false;
  scene_ = initial_scene_;
  dofs_ = resolve_constraints(scene_, n_);
  for (std::size_t c = 0; c < scene_.constraints.size(); ++c)
    moving_[c] = scene_.constraints[c].displacement.squaredNorm() > 0 && scene_.constraints[c].ramp.duration > 0;
  mark_held_nodes();
  dof_work_.assign(dofs_.size(), 0.0);
  dof_force_.assign(dofs_.size(), 0.0);
  load_work_.assign(loads_.size(), 0.0);
  probe_work_ = 0;
  probe_previous_.setZero();
  for (const auto& a : applied_)
    for (int k = 0; k < 3; ++k) applied_force_[3 * a.node + k] = 0.0;
  applied_.clear();
  applied_from_.clear();
  applied_work_ = 0;
  gravity_ramp_work_ = 0;
  removed_energy_ = 0;
  std::fill(contact_force_.begin(), contact_force_.end(), 0.0);
  std::fill(contact_work_.begin(), contact_work_.end(), 0.0);
  tool_force_samples_.assign(scene_.tools.size(), {});
  tool_contact_samples_.assign(scene_.tools.size(), {});
  tool_moved_from_.assign(scene_.tools.size(), Eigen::Vector3d::Zero());
  tool_moved_at_.assign(scene_.tools.size(), -1);
  search_.reset();
  contact_seconds_ = 0;
  next_event_ = 0;
  n_done_ = 0;
  energies_.clear();
  initial_energy_ = initial_bound_ = 0;
  slots_.assign(opt_.threads, ThreadSlot());
  loop_seconds_ = sample_seconds_ = 0;

  for (auto& b : buf_) b.assign(n3, 0.0);
  std::vector<double>& u0 = buf_[1];
  if (!u0_.empty()) u0 = u0_;
  v_start_ = v0_.empty() ? std::vector<double>(n3, 0.0) : v0_;
  std::vector<double>& v0 = v_start_;
  for (const auto& d : dofs_) {
    u0[3 * d.node + d.component] = d.value * scene_.constraints[d.constraint].ramp.at(0.0);
    v0[3 * d.node + d.component] = 0.0;
  }

  // Start-up (000 eq. 33 needs u(−Δt)): u(−Δt) = u0 − Δt v0 + Δt²/2 a0 with the initial
  // acceleration a0 = M⁻¹ (R − F(u0) − D v0).
  fem::KernelStats stats0;
  elements_.reset_law_state();  // a law's internal variables start from zero (law_data.hpp)
  elements_.compute(u0.data(), stats0, fem::StepClock{0, dt});
  if (stats0.min_j <= 0) {
    const MinJ inverted = min_j_element(elements_, u0.data());
    std::ostringstream msg;
    msg << "initial state: element " << inverted.element << " is inverted (J = " << inverted.j << " <= 0)";
    throw NumericalError(msg.str());
  }
  std::vector<double>& um1 = buf_[0];
  const Eigen::Vector3d g0 = gravity_at(0);
  for (int i = 0; i < n_; ++i) {
    double f[3];
    elements_.gather(i, f);
    for (int k = 0; k < 3; ++k) {
      double r = mass_[i] * g0[k];
      const double a = mass_[i] > 0 ? (r - f[k] - opt_.damping_alpha * mass_[i] * v0[3 * i + k]) / mass_[i] : 0.0;
      um1[3 * i + k] = u0[3 * i + k] - dt * v0[3 * i + k] + 0.5 * dt * dt * a;
    }
  }
  // A resumed central-difference state carries its own u(−Δt): no start-up expansion, and the
  // forces acting on it (applied ones included) continue where the previous solver left them.
  if (!u_before_.empty()) um1 = u_before_;
  for (const auto& le : loads_)
    for (int k = 0; k < 3; ++k)
      if (le.free[k] && mass_[le.node] > 0)
        um1[3 * le.node + k] += 0.5 * dt * dt * scene_.loads[le.load].ramp.at(0.0) *
                                scene_.loads[le.load].force_per_node[k] / mass_[le.node];
  if (scene_.has_probe && mass_[scene_.probe.node] > 0) {
    const int i = scene_.probe.node;
    const Eigen::Vector3d fp =
        scene_.probe.stiffness *
        (scene_.probe.tip_displacement(0.0) - Eigen::Vector3d(u0[3 * i], u0[3 * i + 1], u0[3 * i + 2]));
    for (int k = 0; k < 3; ++k) um1[3 * i + k] += 0.5 * dt * dt * fp[k] / mass_[i];
  }
  for (const auto& d : dofs_)
    um1[3 * d.node + d.component] = d.value * scene_.constraints[d.constraint].ramp.at(-dt);
  gravity_booked_potential_ = gravity_ramped_ ? gravity_potential(u0.data()) : 0.0;
  started_ = true;
}

void ExplicitSolver::advance(int steps, const SnapshotFn& snapshot, const ProgressFn& progress) {
  if (steps < 0) throw InputError("solver: the step count must not be negative");
  if (!started_) start();
  const int T = opt_.threads;
  const long long target = static_cast<long long>(n_done_) + steps;
  if (target > std::numeric_limits<int>::max()) throw InputError("solver: the step count exceeds the int range");
  const bool nodal_pressure = elements_.has_nodal_pressure();
  const bool law_state = elements_.has_law_state();
  auto& buf = buf_;
  const auto t_loop = Clock::now();
  fire_due_events();
  while (n_done_ < target) {
    // The one step from the previous step size to a new one is done; back to equal steps.
    if (transition_ && n_done_ > segments_.back().first_step) {
      set_coefficients(segments_.back().dt, segments_.back().dt);
      transition_ = false;
    }
    // Next stop: an energy sample (after steps 1, 1 + interval, ...), a snapshot, a step
    // re-estimate, the end of a step-size transition, or the end.
    // In 64 bits: with an interval near the int range the next multiple lies beyond it.
    long long stop = target;
    const long long ei = opt_.energy_interval;
    const long long n_done = n_done_;
    if (transition_) stop = std::min(stop, n_done + 1);
    if (opt_.adapt_step) {
      const long long ci = opt_.step_check_interval;
      stop = std::min(stop, (n_done / ci + 1) * ci);
    }
    const long long next_sample = n_done < 1 ? 1 : ((n_done - 1) / ei + 1) * ei + 1;
    stop = std::min(stop, next_sample);
    if (opt_.steps > n_done) stop = std::min<long long>(stop, opt_.steps);
    if (next_event_ < opt_.event_times.size()) {
      // The first step whose time reaches the event (within the current step size).
      const double ahead = (opt_.event_times[next_event_] - time()) / dt();
      stop = std::min(stop, n_done + std::max(1LL, static_cast<long long>(std::ceil(ahead - 1e-9))));
    }
    if (opt_.snapshot_interval > 0) {
      const long long si = opt_.snapshot_interval;
      stop = std::min(stop, (n_done / si + 1) * si);
    }
    const int s_begin = n_done_, s_end = static_cast<int>(stop);
    int failed_step = -1;
    bool failed_inversion = false;

    parallel(T, [&](int tid, int nthreads) {
      ThreadSlot& me = slots_[tid];
      for (int s = s_begin; s < s_end; ++s) {
        const double* up = buf[s % 3].data();
        const double* uc = buf[(s + 1) % 3].data();
        double* un = buf[(s + 2) % 3].data();
        // Timing is sampled on one step in kTimingStride to keep clock reads out of the loop.
        const bool timed = s % kTimingStride == 0;
        if (timed) ++me.timed_steps;
        fem::KernelStats st;
        double check = 0.0;
        const Eigen::Vector3d g = gravity_at(s);
        if (tid == 0) book_gravity_work(s, uc);  // reads u_s, which step s does not write
        if (nodal_pressure) {
          // ANP pre-pass: det F of the ANP elements, then the nodal pressures they need.
          for (int p = tid; p < T; p += nthreads)
            for (int q = tile_begin_[p]; q < tile_begin_[p + 1]; ++q) elements_.compute_volume_ratios(uc, q, st);
          barrier();
          for (int p = tid; p < T; p += nthreads)
            elements_.update_nodal_pressures(pressure_nodes_[p], pressure_nodes_[p + 1]);
          barrier();
        }
        const fem::StepClock clock = law_state ? fem::StepClock{s, step_size(s)} : fem::StepClock{};
        for (int p = tid; p < T; p += nthreads)
          for (int q = tile_begin_[p]; q < tile_begin_[p + 1]; ++q) {
            elements_.compute_tile(uc, q, st, timed ? me.kernel_seconds.data() : nullptr, clock);
            const auto t0 = timed ? Clock::now() : Clock::time_point();
            update_nodes(local_nodes_.data(), local_begin_[q], local_split_[q], local_begin_[q + 1], s, up, uc, un, check,
                         g);
            if (timed) me.node_seconds += seconds_since(t0);
          }
        me.min_j = st.min_j;
        barrier();
        double gmin = 1e300;
        for (int q = 0; q < nthreads; ++q) gmin = std::min(gmin, slots_[q].min_j);
        if (gmin <= 0) {
          if (tid == 0) {
            failed_step = s;
            failed_inversion = true;
          }
          break;
        }
        const auto t0 = timed ? Clock::now() : Clock::time_point();
        for (int p = tid; p < T; p += nthreads)
          update_nodes(deferred_nodes_.data(), deferred_begin_[p], deferred_split_[p], deferred_begin_[p + 1], s, up,
                       uc, un, check, g);
        if (timed) me.node_seconds += seconds_since(t0);
        me.bad = !(check == 0.0);
        barrier();
        bool any_bad = false;
        for (int q = 0; q < nthreads; ++q) any_bad = any_bad || slots_[q].bad;
        if (any_bad) {
          if (tid == 0) failed_step = s;
          break;
        }
        if (!contact_begin_.empty() && contact_begin_.back() > 0) {  // rigid tools: one thread, then the others wait
          if (tid == 0) {
            const auto tc = timed ? Clock::now() : Clock::time_point();
            contact_pass(s, up, uc, un);
            if (timed) contact_seconds_ += seconds_since(tc);
          }
          barrier();
        }
      }
    });

    if (failed_step >= 0) {
      started_ = false;  // the state is no longer a solution: the next advance() starts over
      const double* u = buf[(failed_step + (failed_inversion ? 1 : 2)) % 3].data();
      // The last sound state: u_{s−1} before an inversion found at u_s, u_s before a non-finite u_{s+1}.
      const double* sound = buf[(failed_step + (failed_inversion ? 0 : 1)) % 3].data();
      std::ostringstream msg;
      if (failed_inversion) {
        const MinJ inverted = min_j_element(elements_, u);
        msg << "element " << inverted.element << " (" << fem::kind_name(elements_.kinds()[inverted.element])
            << ") is inverted: J = " << inverted.j << " <= 0";
        if (failed_step > 0) fail_step_size(failed_step, sound, msg.str());
        fail_inversion(failed_step, inverted.j, inverted.element);
      }
      int node = -1;
      for (int q = 0; q < 3 * n_ && node < 0; ++q)
        if (!std::isfinite(u[q])) node = q / 3;
      msg << "displacement of node " << node << " is not finite (NaN or overflow); dt = " << step_size(failed_step)
          << " s";
      fail_step_size(failed_step, sound, msg.str());
    }
    n_done_ = s_end;
    sample(snapshot);
    fire_due_events();
    if (opt_.adapt_step && n_done_ % opt_.step_check_interval == 0) {
      const auto ts = Clock::now();
      check_step();
      sample_seconds_ += seconds_since(ts);
    }
    if (progress) progress(n_done_, time());
  }
  loop_seconds_ += seconds_since(t_loop);
}

// The energy sample, checks and snapshot due after the steps done.
void ExplicitSolver::sample(const SnapshotFn& snapshot) {
  const int n_done = n_done_;
  const double dt = step_size(n_done - 1);
  const int n3 = 3 * n_;
  auto& buf = buf_;
  const bool sample_due = (n_done - 1) % opt_.energy_interval == 0 || n_done == opt_.steps;
  if (sample_due) {
    const auto ts = Clock::now();
    // After n steps: u_{n−2} = buf[(n−1)%3], u_{n−1} = buf[n%3], u_n = buf[(n+1)%3].
    double mj = 1e300, bound_kinetic = 0;
    int me = -1;
    EnergySample s = sample_energy(n_done, buf[(n_done - 1) % 3].data(), buf[n_done % 3].data(),
                                   buf[(n_done + 1) % 3].data(), bound_kinetic, mj, me);
    if (mj <= 0) {
      started_ = false;
      fail_inversion(n_done - 1, mj, me);
    }
    if (energies_.empty()) {
      initial_energy_ = s.kinetic + s.strain - s.external_work;
      initial_bound_ = bound_kinetic + s.strain;
    }
    s.removed = removed_energy_;
    s.dissipated = initial_energy_ + s.external_work - s.kinetic - s.strain - s.removed;
    energies_.push_back(s);
    if (!scene_.tools.empty()) record_tool_forces();
    const double mechanical = bound_kinetic + s.strain;
    // The conserved (half-step) kinetic energy cannot reveal an instability (it stays balanced
    // even while a mode grows), so the check uses the non-negative mean of the half-step
    // kinetic energies.
    const double limit =
        opt_.energy_growth_limit * (std::max(initial_bound_, 0.0) + std::max(s.external_work, 0.0)) + energy_floor_;
    if (!(mechanical <= limit)) {
      started_ = false;
      std::ostringstream msg;
      msg << "kinetic + strain energy " << mechanical << " J exceeds " << opt_.energy_growth_limit
          << " x (initial energy + external work) = " << limit << " J: the integration is unstable (dt = " << dt
          << " s)";
      fail_step_size(n_done - 1, buf[n_done % 3].data(), msg.str());
    }
    sample_seconds_ += seconds_since(ts);
  }
  if (snapshot && opt_.snapshot_interval > 0 && n_done % opt_.snapshot_interval == 0) {
    const std::vector<double>& un = buf[(n_done + 1) % 3];
    snapshot_velocity_.resize(n3);
    velocity(snapshot_velocity_.data());
    const auto ts = Clock::now();
    snapshot(n_done, time(), un, snapshot_velocity_);
    sample_seconds_ += seconds_since(ts);
  }
}

void ExplicitSolver::velocity(double* out) const {
  const int n3 = 3 * n_;
  if (n_done_ == 0) {
    if (v_start_.empty()) std::fill(out, out + n3, 0.0);
    else std::copy(v_start_.begin(), v_start_.end(), out);
    return;
  }
  const double* u = buf_[(n_done_ + 1) % 3].data();
  const double* before = buf_[n_done_ % 3].data();
  const double dt = step_size(n_done_ - 1);
  for (int q = 0; q < n3; ++q) out[q] = (u[q] - before[q]) / dt;
}

std::vector<Eigen::Vector3d> ExplicitSolver::reactions() {
  if (!started_) start();
  // Quasi-static reactions: internal force minus applied load. (The next step recomputes the
  // element forces from the same state, so this pass leaves the stepping unchanged.)
  const double* u = displacement();
  fem::KernelStats st;
  elements_.compute(u, st, fem::StepClock{n_done_, step_size(n_done_)});  // step n_done_'s forces, state unmoved
  std::vector<Eigen::Vector3d> reactions(scene_.constraints.size(), Eigen::Vector3d::Zero());
  const double t = time();
  for (const auto& d : dofs_) {
    double f[3];
    elements_.gather(d.node, f);
    double r = f[d.component] - mass_[d.node] * scene_.gravity[d.component] * (gravity_ramped_ ? scene_.gravity_ramp.at(t) : 1.0);
    for (int e = load_begin_[d.node]; e < load_begin_[d.node + 1]; ++e) {
      const NodalLoad& load = scene_.loads[loads_[e].load];
      r -= load.ramp.at(t) * load.force_per_node[d.component];
    }
    if (scene_.has_probe && scene_.probe.node == d.node)
      r -= scene_.probe.stiffness * (scene_.probe.tip_displacement(t)[d.component] - u[3 * d.node + d.component]);
    reactions[d.constraint][d.component] += r;
  }
  return reactions;
}

Eigen::Vector3d ExplicitSolver::probe_force() const {
  if (!scene_.has_probe || !started_) return Eigen::Vector3d::Zero();
  const int i = scene_.probe.node;
  const double* u = displacement();
  return scene_.probe.stiffness *
         (scene_.probe.tip_displacement(time()) - Eigen::Vector3d(u[3 * i], u[3 * i + 1], u[3 * i + 2]));
}

void ExplicitSolver::set_prescribed_displacement(int c, const Eigen::Vector3d& value) {
  if (c < 0 || c >= static_cast<int>(scene_.constraints.size()))
    throw InputError("constraint " + std::to_string(c) + " out of range (the scene has " +
                     std::to_string(scene_.constraints.size()) + ")");
  if (!value.allFinite()) throw InputError("constraint \"" + scene_.constraints[c].name + "\": value is not finite");
  if (!started_) start();
  scene_.constraints[c].displacement = value;
  scene_.constraints[c].ramp.duration = 0;
  for (auto& d : dofs_)
    if (d.constraint == c) {
      d.value = value[d.component];
      held_[d.node] = 0;  // a driven constraint needs its nodes' internal force
    }
  // Work is booked from the next step on; a dof that was held fixed did no work before it.
  moving_[c] = 1;
}

void ExplicitSolver::set_probe_tip(const Eigen::Vector3d& tip_displacement) {
  if (!scene_.has_probe) throw InputError("probe: the scene has no probe");
  if (!tip_displacement.allFinite()) throw InputError("probe: tip position is not finite");
  if (!started_) start();
  scene_.probe.displacement = tip_displacement;
  scene_.probe.ramp.duration = 0;
}

void ExplicitSolver::set_applied_forces(const std::vector<AppliedForce>& forces) {
  for (const auto& a : forces) {
    if (a.node < 0 || a.node >= n_) throw InputError("applied force: node " + std::to_string(a.node) + " out of range");
    if (!a.force.allFinite()) throw InputError("applied force on node " + std::to_string(a.node) + " is not finite");
  }
  if (!started_) start();
  // The work of the set that stops acting now: after n steps it has acted up to u_{n−1}; the
  // force of step n − 1 moves u_{n−1} to u_n, so book up to u_n (the current state).
  const double* u = displacement();
  for (std::size_t a = 0; a < applied_.size(); ++a)
    for (int k = 0; k < 3; ++k) {
      const int q = 3 * applied_[a].node + k;
      if (!constrained_[q]) applied_work_ += applied_[a].force[k] * (u[q] - applied_from_[3 * a + k]);
      applied_force_[q] = 0.0;
    }
  if (applied_force_.empty()) applied_force_.assign(3 * n_, 0.0);
  applied_ = forces;
  applied_from_.resize(3 * forces.size());
  for (std::size_t a = 0; a < forces.size(); ++a)
    for (int k = 0; k < 3; ++k) {
      const int q = 3 * forces[a].node + k;
      applied_force_[q] += forces[a].force[k];
      applied_from_[3 * a + k] = u[q];
    }
}

// The step re-estimate: once the step in use exceeds the critical step of the current state, the
// next step becomes step_safety × that critical step (000 eq. 34 on the deformed mesh). The
// next step is the transition from the old size to the new one (variable-step central
// difference, see central_difference.hpp); equal steps follow.
void ExplicitSolver::check_step() {
  const double critical = opt_.critical_step(displacement());
  const double dt_now = dt();
  if (!(dt_now > critical)) return;
  const double dt_new = opt_.step_safety * critical;
  if (!(dt_new > 0)) {
    started_ = false;
    std::ostringstream msg;
    msg << where(n_done_) << ": step-size failure: the critical step of the deformed mesh is " << critical
        << " s (000 eq. 34 on the current geometry): an element is flat or inverted";
    throw NumericalError(msg.str());
  }
  const double t = time();
  if (segments_.back().first_step == n_done_) segments_.back() = StepSegment{n_done_, t, dt_new};
  else segments_.push_back(StepSegment{n_done_, t, dt_new});
  set_coefficients(step_size(n_done_ - 1), dt_new);
  transition_ = true;
}

ExplicitTiming ExplicitSolver::timing() const {
  ExplicitTiming tm;
  tm.threads = opt_.threads;
  tm.wall_seconds = loop_seconds_;
  const double stepping = loop_seconds_ - sample_seconds_;
  tm.steps_per_second = stepping > 0 ? n_done_ / stepping : 0;
  // Sampled timings scaled to all steps.
  int timed = 0;
  for (const auto& s : slots_) timed = std::max(timed, s.timed_steps);
  const double scale = timed > 0 ? static_cast<double>(n_done_) / timed : 0.0;
  for (const auto& s : slots_) {
    for (int k = 0; k < fem::kNumElementKinds; ++k) tm.kernel_seconds[k] += scale * s.kernel_seconds[k];
    tm.node_seconds += scale * s.node_seconds;
  }
  for (int k = 0; k < fem::kNumElementKinds; ++k) tm.element_counts[k] = elements_.count(static_cast<fem::ElementKind>(k));
  tm.sample_seconds = sample_seconds_;
  tm.contact_seconds = scale * contact_seconds_;
  return tm;
}

ExplicitResult ExplicitSolver::run(const SnapshotFn& snapshot, const ProgressFn& progress) {
  const double dt = opt_.dt;
  reset();
  ExplicitResult res;
  res.steps = opt_.steps;
  res.dt = dt;

  // Recording buffers.
  // Sized in 64 bits (steps / 1 + 1 exceeds the int range); no clock without trajectories.
  const double* u0 = displacement();
  const std::size_t n_traj_samples =
      opt_.trajectory_nodes.empty() ? 0 : static_cast<std::size_t>(opt_.steps / opt_.trajectory_interval) + 1;
  res.trajectories.assign(opt_.trajectory_nodes.size(), std::vector<Eigen::Vector3d>(n_traj_samples));
  for (std::size_t j = 0; j < opt_.trajectory_nodes.size(); ++j) {
    const int i = opt_.trajectory_nodes[j];
    res.trajectories[j][0] = Eigen::Vector3d(u0[3 * i], u0[3 * i + 1], u0[3 * i + 2]);
  }
  const int n_probe_samples = opt_.steps > 0 ? (opt_.steps - 1) / opt_.trajectory_interval + 1 : 0;
  if (scene_.has_probe) res.probe_force.assign(n_probe_samples, Eigen::Vector3d::Zero());
  trajectories_ = &res.trajectories;
  probe_force_ = scene_.has_probe ? &res.probe_force : nullptr;
  struct ClearTargets {
    ExplicitSolver* s;
    ~ClearTargets() {
      s->trajectories_ = nullptr;
      s->probe_force_ = nullptr;
    }
  } clear_targets{this};

  if (snapshot && opt_.snapshot_interval > 0) snapshot(0, 0.0, buf_[1], v_start_);
  advance(opt_.steps, snapshot, progress);
  // Sample times once the step sizes are known.
  for (std::size_t s = 0; s < n_traj_samples; ++s)
    res.trajectory_time.push_back(time_at(static_cast<int>(s) * opt_.trajectory_interval));
  if (scene_.has_probe)
    for (int s = 0; s < n_probe_samples; ++s) res.probe_time.push_back(time_at(s * opt_.trajectory_interval));
  res.time = time();
  res.step_history = segments_;

  const int n3 = 3 * n_;  // after the steps: a separating cut adds nodes
  res.displacement.assign(displacement(), displacement() + n3);
  res.velocity.resize(n3);
  velocity(res.velocity.data());
  res.energies = energies_;
  res.tool_force = tool_force_samples_;
  res.tool_contacts = tool_contact_samples_;
  res.reactions = reactions();
  res.timing = timing();
  return res;
}

}  // namespace softsim::dynamics
