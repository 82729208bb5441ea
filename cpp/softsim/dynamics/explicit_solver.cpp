#include "softsim/dynamics/explicit_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#if defined(SOFTSIM_HAVE_OPENMP)
#include <omp.h>
#endif

#include "softsim/dynamics/central_difference.hpp"
#include "softsim/io/errors.hpp"

namespace softsim::dynamics {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Runs body(thread, threads) on `threads` OpenMP threads (or inline without OpenMP).
template <class Body>
void parallel(int threads, Body&& body) {
#if defined(SOFTSIM_HAVE_OPENMP)
  if (threads > 1) {
#pragma omp parallel num_threads(threads)
    body(omp_get_thread_num(), omp_get_num_threads());
    return;
  }
#endif
  body(0, 1);
}

inline void barrier() {
#if defined(SOFTSIM_HAVE_OPENMP)
#pragma omp barrier
#endif
}

// Per-thread slots on separate cache lines.
struct alignas(64) ThreadSlot {
  double min_j = 1e300;
  bool bad = false;
  std::array<double, fem::kNumElementKinds> kernel_seconds{};
  double node_seconds = 0;
};

std::string where(int step, double dt) {
  std::ostringstream s;
  s << "explicit step " << step << " (t = " << step * dt << " s)";
  return s.str();
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

  A_.resize(n_);
  B_.resize(n_);
  C_.resize(n_);
  Am_.resize(n_);
  for (int i = 0; i < n_; ++i) {
    const CentralDifference cd = central_difference(mass_[i], opt_.damping_alpha, opt_.dt);
    A_[i] = cd.A;
    B_[i] = cd.B;
    C_[i] = cd.C;
    Am_[i] = cd.A * mass_[i];
  }
  gravity_ = scene_.gravity.squaredNorm() > 0;

  dofs_ = resolve_constraints(scene_, n_);
  const std::vector<char> mask = constrained_mask(dofs_, n_);
  moving_.assign(scene_.constraints.size(), 0);
  for (std::size_t c = 0; c < scene_.constraints.size(); ++c)
    moving_[c] = scene_.constraints[c].displacement.squaredNorm() > 0 && scene_.constraints[c].ramp.duration > 0;
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

  element_ranges_ = elements_.balanced_ranges(opt_.threads);
  const int T = opt_.threads;
  node_ranges_.resize(T + 1);
  for (int p = 0; p <= T; ++p) node_ranges_[p] = static_cast<int>(static_cast<long long>(n_) * p / T);
  trajectory_order_.resize(opt_.trajectory_nodes.size());
  for (std::size_t j = 0; j < trajectory_order_.size(); ++j) trajectory_order_[j] = static_cast<int>(j);
  std::stable_sort(trajectory_order_.begin(), trajectory_order_.end(),
                   [&](int a, int b) { return opt_.trajectory_nodes[a] < opt_.trajectory_nodes[b]; });
  dof_ranges_.resize(T + 1);
  load_ranges_.resize(T + 1);
  trajectory_ranges_.resize(T + 1);
  for (int p = 0; p <= T; ++p) {
    const int first = node_ranges_[p];
    dof_ranges_[p] = static_cast<int>(
        std::lower_bound(dofs_.begin(), dofs_.end(), first, [](const ConstrainedDof& d, int v) { return d.node < v; }) -
        dofs_.begin());
    load_ranges_[p] = static_cast<int>(
        std::lower_bound(loads_.begin(), loads_.end(), first, [](const LoadEntry& e, int v) { return e.node < v; }) -
        loads_.begin());
    trajectory_ranges_[p] = static_cast<int>(
        std::lower_bound(trajectory_order_.begin(), trajectory_order_.end(), first,
                         [&](int j, int v) { return opt_.trajectory_nodes[j] < v; }) -
        trajectory_order_.begin());
  }
}

void ExplicitSolver::set_initial_state(std::vector<double> u0, std::vector<double> v0) {
  if (!u0.empty() && static_cast<int>(u0.size()) != 3 * n_) throw std::invalid_argument("initial displacement size");
  if (!v0.empty() && static_cast<int>(v0.size()) != 3 * n_) throw std::invalid_argument("initial velocity size");
  u0_ = std::move(u0);
  v0_ = std::move(v0);
}

// Gather, central-difference update (000 eq. 33) and the scene's special nodes, for the nodes
// of range `part`. Everything a node needs is done by the thread owning its range.
void ExplicitSolver::node_phase(int part, int step, const double* up, const double* uc, double* un, bool& bad) {
  const double dt = opt_.dt;
  const double t = step * dt;
  const int nb = node_ranges_[part], ne = node_ranges_[part + 1];
  const double gx = scene_.gravity.x(), gy = scene_.gravity.y(), gz = scene_.gravity.z();
  double check = 0.0;
  for (int i = nb; i < ne; ++i) {
    double f[3];
    elements_.gather(i, f);
    const double a = A_[i], b = B_[i], c = C_[i];
    double x = b * uc[3 * i] - c * up[3 * i] - a * f[0];
    double y = b * uc[3 * i + 1] - c * up[3 * i + 1] - a * f[1];
    double z = b * uc[3 * i + 2] - c * up[3 * i + 2] - a * f[2];
    if (gravity_) {
      const double am = Am_[i];
      x += am * gx;
      y += am * gy;
      z += am * gz;
    }
    un[3 * i] = x;
    un[3 * i + 1] = y;
    un[3 * i + 2] = z;
    check += (x - x) + (y - y) + (z - z);  // NaN as soon as any value is not finite
  }
  if (!(check == 0.0)) bad = true;

  // Nodal loads: R enters eq. 33 as + A R.
  const int l_end = load_ranges_[part + 1];
  for (int e = load_ranges_[part]; e < l_end; ++e) {
    const LoadEntry& le = loads_[e];
    const NodalLoad& load = scene_.loads[le.load];
    const double r = load.ramp.at(t);
    for (int k = 0; k < 3; ++k)
      if (le.free[k]) un[3 * le.node + k] += A_[le.node] * r * load.force_per_node[k];
  }
  // The probe spring pulls its node towards the tool tip.
  Eigen::Vector3d probe_force = Eigen::Vector3d::Zero();
  const bool probe_here = scene_.has_probe && scene_.probe.node >= nb && scene_.probe.node < ne;
  if (probe_here) {
    const int i = scene_.probe.node;
    const Eigen::Vector3d ui(uc[3 * i], uc[3 * i + 1], uc[3 * i + 2]);
    probe_force = scene_.probe.stiffness * (scene_.probe.displacement * scene_.probe.ramp.at(t) - ui);
    for (int k = 0; k < 3; ++k)
      if (probe_free_[k]) un[3 * i + k] += A_[i] * probe_force[k];
    if (probe_force_ && step % opt_.trajectory_interval == 0)
      (*probe_force_)[step / opt_.trajectory_interval] = probe_force;
  }
  // Constraints overwrite. External work is booked on [t − Δt, t] with the trapezoidal rule,
  // ½ (f(t − Δt) + f(t)) · (u(t) − u(t − Δt)), the form the central-difference energy balance
  // takes; a moving constraint's force is the one that produces its motion, M a + D v + F.
  const int d_end = dof_ranges_[part + 1];
  const double alpha = opt_.damping_alpha;
  for (int e = dof_ranges_[part]; e < d_end; ++e) {
    const ConstrainedDof& d = dofs_[e];
    const int q = 3 * d.node + d.component;
    const double value = d.value * scene_.constraints[d.constraint].ramp.at(t + dt);
    if (moving_[d.constraint]) {
      double f[3];
      elements_.gather(d.node, f);
      const double m = mass_[d.node];
      const double total =
          m * (value - 2.0 * uc[q] + up[q]) / (dt * dt) + alpha * m * (value - up[q]) / (2.0 * dt) + f[d.component];
      if (step > 0) dof_work_[e] += 0.5 * (dof_force_[e] + total) * (uc[q] - up[q]);
      dof_force_[e] = total;
    }
    un[q] = value;
  }
  if (step > 0) {
    for (int e = load_ranges_[part]; e < l_end; ++e) {
      const LoadEntry& le = loads_[e];
      const NodalLoad& load = scene_.loads[le.load];
      const double r = 0.5 * (load.ramp.at(t - dt) + load.ramp.at(t));
      double w = 0;
      for (int k = 0; k < 3; ++k)
        if (le.free[k]) w += r * load.force_per_node[k] * (uc[3 * le.node + k] - up[3 * le.node + k]);
      load_work_[e] += w;
    }
  }
  if (probe_here) {
    const int i = scene_.probe.node;
    if (step > 0)
      for (int k = 0; k < 3; ++k)
        if (probe_free_[k]) probe_work_ += 0.5 * (probe_previous_[k] + probe_force[k]) * (uc[3 * i + k] - up[3 * i + k]);
    probe_previous_ = probe_force;
  }
  if (trajectories_ && (step + 1) % opt_.trajectory_interval == 0) {
    const int sample = (step + 1) / opt_.trajectory_interval;
    for (int j = trajectory_ranges_[part]; j < trajectory_ranges_[part + 1]; ++j) {
      const int jj = trajectory_order_[j];
      const int i = opt_.trajectory_nodes[jj];
      (*trajectories_)[jj][sample] = Eigen::Vector3d(un[3 * i], un[3 * i + 1], un[3 * i + 2]);
    }
  }
}

double ExplicitSolver::external_work() const {
  double w = probe_work_;
  for (double x : dof_work_) w += x;
  for (double x : load_work_) w += x;
  return w;
}

EnergySample ExplicitSolver::sample_energy(int n_done, const double* u_before, const double* u_mid,
                                           const double* u_after, double& bound_kinetic, double& min_j,
                                           int& min_j_element) {
  // Time t_{n−1}, strain energy at u_{n−1}. The kinetic energy is the one the central-difference
  // scheme conserves exactly for a linear undamped system: ½ v⁻·M v⁺ with the half-step
  // velocities around t_{n−1}; `bound_kinetic` = ½ (|v⁻|²_M + |v⁺|²_M)/2 ≥ 0 for the growth check.
  const double dt = opt_.dt;
  EnergySample s;
  s.time = (n_done - 1) * dt;
  double kinetic = 0, bound = 0, gravity_work = 0;
  for (int i = 0; i < n_; ++i)
    for (int k = 0; k < 3; ++k) {
      const int q = 3 * i + k;
      const double vm = (u_mid[q] - u_before[q]) / dt, vp = (u_after[q] - u_mid[q]) / dt;
      kinetic += 0.5 * mass_[i] * vm * vp;
      bound += 0.25 * mass_[i] * (vm * vm + vp * vp);
      gravity_work += mass_[i] * scene_.gravity[k] * u_mid[q];
    }
  bound_kinetic = bound;
  std::vector<double> energy(elements_.padded_size(), 0.0);
  std::vector<double> part_min(opt_.threads, 1e300);
  std::vector<int> part_elem(opt_.threads, -1);
  parallel(opt_.threads, [&](int tid, int nthreads) {
    for (int p = tid; p < opt_.threads; p += nthreads)
      elements_.energies(u_mid, element_ranges_[p], element_ranges_[p + 1], energy.data(), part_min[p], part_elem[p]);
  });
  for (int p = 0; p < opt_.threads; ++p)
    if (part_min[p] < min_j) {
      min_j = part_min[p];
      min_j_element = part_elem[p];
    }
  double strain = 0;
  for (double e : energy) strain += e;
  s.kinetic = kinetic;
  s.strain = strain;
  s.external_work = external_work() + gravity_work;
  return s;
}

ExplicitResult ExplicitSolver::run(const SnapshotFn& snapshot) {
  const int n3 = 3 * n_;
  const double dt = opt_.dt;
  const int T = opt_.threads;
  ExplicitResult res;
  res.steps = opt_.steps;
  res.dt = dt;
  res.time = opt_.steps * dt;
  dof_work_.assign(dofs_.size(), 0.0);
  dof_force_.assign(dofs_.size(), 0.0);
  load_work_.assign(loads_.size(), 0.0);
  probe_work_ = 0;

  std::array<std::vector<double>, 3> buf;
  for (auto& b : buf) b.assign(n3, 0.0);
  std::vector<double>& u0 = buf[1];
  if (!u0_.empty()) u0 = u0_;
  std::vector<double> v0 = v0_.empty() ? std::vector<double>(n3, 0.0) : v0_;
  for (const auto& d : dofs_) {
    u0[3 * d.node + d.component] = d.value * scene_.constraints[d.constraint].ramp.at(0.0);
    v0[3 * d.node + d.component] = 0.0;
  }

  // Start-up (000 eq. 33 needs u(−Δt)): u(−Δt) = u0 − Δt v0 + Δt²/2 a0 with the initial
  // acceleration a0 = M⁻¹ (R − F(u0) − D v0).
  fem::KernelStats stats0;
  elements_.compute(u0.data(), 0, elements_.padded_size(), stats0);
  if (stats0.min_j <= 0) {
    double mj = 1e300;
    int me = -1;
    std::vector<double> scratch(elements_.padded_size());
    elements_.energies(u0.data(), 0, elements_.padded_size(), scratch.data(), mj, me);
    std::ostringstream msg;
    msg << "initial state: element " << me << " is inverted (J = " << mj << " <= 0)";
    throw NumericalError(msg.str());
  }
  std::vector<double>& um1 = buf[0];
  for (int i = 0; i < n_; ++i) {
    double f[3];
    elements_.gather(i, f);
    for (int k = 0; k < 3; ++k) {
      double r = mass_[i] * scene_.gravity[k];
      const double a = mass_[i] > 0 ? (r - f[k] - opt_.damping_alpha * mass_[i] * v0[3 * i + k]) / mass_[i] : 0.0;
      um1[3 * i + k] = u0[3 * i + k] - dt * v0[3 * i + k] + 0.5 * dt * dt * a;
    }
  }
  for (const auto& le : loads_)
    for (int k = 0; k < 3; ++k)
      if (le.free[k] && mass_[le.node] > 0)
        um1[3 * le.node + k] += 0.5 * dt * dt * scene_.loads[le.load].ramp.at(0.0) *
                                scene_.loads[le.load].force_per_node[k] / mass_[le.node];
  if (scene_.has_probe && mass_[scene_.probe.node] > 0) {
    const int i = scene_.probe.node;
    const Eigen::Vector3d fp =
        scene_.probe.stiffness * (scene_.probe.displacement * scene_.probe.ramp.at(0.0) -
                                  Eigen::Vector3d(u0[3 * i], u0[3 * i + 1], u0[3 * i + 2]));
    for (int k = 0; k < 3; ++k) um1[3 * i + k] += 0.5 * dt * dt * fp[k] / mass_[i];
  }
  for (const auto& d : dofs_)
    um1[3 * d.node + d.component] = d.value * scene_.constraints[d.constraint].ramp.at(-dt);

  // Recording buffers.
  const int n_traj_samples = opt_.steps / opt_.trajectory_interval + 1;
  res.trajectories.assign(opt_.trajectory_nodes.size(), std::vector<Eigen::Vector3d>(n_traj_samples));
  for (std::size_t j = 0; j < opt_.trajectory_nodes.size(); ++j) {
    const int i = opt_.trajectory_nodes[j];
    res.trajectories[j][0] = Eigen::Vector3d(u0[3 * i], u0[3 * i + 1], u0[3 * i + 2]);
  }
  for (int s = 0; s < n_traj_samples; ++s) res.trajectory_time.push_back(s * opt_.trajectory_interval * dt);
  const int n_probe_samples = opt_.steps > 0 ? (opt_.steps - 1) / opt_.trajectory_interval + 1 : 0;
  if (scene_.has_probe) {
    res.probe_force.assign(n_probe_samples, Eigen::Vector3d::Zero());
    for (int s = 0; s < n_probe_samples; ++s) res.probe_time.push_back(s * opt_.trajectory_interval * dt);
  }
  trajectories_ = &res.trajectories;
  probe_force_ = scene_.has_probe ? &res.probe_force : nullptr;

  if (snapshot && opt_.snapshot_interval > 0) snapshot(0, 0.0, u0, v0);

  std::vector<ThreadSlot> slots(T);
  double total_mass = 0;
  for (double m : mass_) total_mass += m;
  const double total_volume = total_mass / elements_.material().elastic.density;
  const double energy_floor = 1e-12 * elements_.material().elastic.youngs_modulus * total_volume;
  double initial_energy = 0, initial_bound = 0;
  double sample_seconds = 0;

  auto fail_linear_inversion = [&](int step, double J, int e) {
    std::ostringstream msg;
    msg << where(step, dt) << ": element " << e << " (" << fem::kind_name(elements_.kinds()[e])
        << ") is inverted: J = " << J << " <= 0";
    throw NumericalError(msg.str());
  };

  int n_done = 0;
  const auto t_loop = Clock::now();
  while (n_done < opt_.steps) {
    // Next stop: an energy sample (after steps 1, 1 + interval, ...), a snapshot, or the end.
    int stop = opt_.steps;
    const int ei = opt_.energy_interval;
    const int next_sample = n_done < 1 ? 1 : ((n_done - 1) / ei + 1) * ei + 1;
    stop = std::min(stop, next_sample);
    if (opt_.snapshot_interval > 0) stop = std::min(stop, (n_done / opt_.snapshot_interval + 1) * opt_.snapshot_interval);
    const int s_begin = n_done, s_end = stop;
    int failed_step = -1;
    bool failed_inversion = false;

    parallel(T, [&](int tid, int nthreads) {
      ThreadSlot& me = slots[tid];
      for (int s = s_begin; s < s_end; ++s) {
        const double* up = buf[s % 3].data();
        const double* uc = buf[(s + 1) % 3].data();
        double* un = buf[(s + 2) % 3].data();
        fem::KernelStats st;
        for (int p = tid; p < T; p += nthreads)
          elements_.compute(uc, element_ranges_[p], element_ranges_[p + 1], st, me.kernel_seconds.data());
        me.min_j = st.min_j;
        barrier();
        double gmin = 1e300;
        for (int q = 0; q < nthreads; ++q) gmin = std::min(gmin, slots[q].min_j);
        if (gmin <= 0) {
          if (tid == 0) {
            failed_step = s;
            failed_inversion = true;
          }
          break;
        }
        const auto t0 = Clock::now();
        bool bad = false;
        for (int p = tid; p < T; p += nthreads) node_phase(p, s, up, uc, un, bad);
        me.bad = bad;
        me.node_seconds += seconds_since(t0);
        barrier();
        bool any_bad = false;
        for (int q = 0; q < nthreads; ++q) any_bad = any_bad || slots[q].bad;
        if (any_bad) {
          if (tid == 0) failed_step = s;
          break;
        }
      }
    });

    if (failed_step >= 0) {
      const double* u = buf[(failed_step + (failed_inversion ? 1 : 2)) % 3].data();
      double mj = 1e300;
      int me = -1;
      std::vector<double> scratch(elements_.padded_size());
      elements_.energies(u, 0, elements_.padded_size(), scratch.data(), mj, me);
      std::ostringstream msg;
      if (failed_inversion) {
        msg << where(failed_step, dt) << ": element " << me << " (" << fem::kind_name(elements_.kinds()[me])
            << ") is inverted: J = " << mj << " <= 0";
      } else {
        int node = -1;
        for (int q = 0; q < n3 && node < 0; ++q)
          if (!std::isfinite(u[q])) node = q / 3;
        msg << where(failed_step, dt) << ": displacement of node " << node
            << " is not finite (NaN or overflow); dt = " << dt << " s";
      }
      throw NumericalError(msg.str());
    }
    n_done = stop;

    const bool sample_due = (n_done - 1) % opt_.energy_interval == 0 || n_done == opt_.steps;
    if (sample_due) {
      const auto ts = Clock::now();
      // After n steps: u_{n−2} = buf[(n−1)%3], u_{n−1} = buf[n%3], u_n = buf[(n+1)%3].
      double mj = 1e300, bound_kinetic = 0;
      int me = -1;
      EnergySample s = sample_energy(n_done, buf[(n_done - 1) % 3].data(), buf[n_done % 3].data(),
                                     buf[(n_done + 1) % 3].data(), bound_kinetic, mj, me);
      if (mj <= 0) fail_linear_inversion(n_done - 1, mj, me);
      if (res.energies.empty()) {
        initial_energy = s.kinetic + s.strain - s.external_work;
        initial_bound = bound_kinetic + s.strain;
      }
      s.dissipated = initial_energy + s.external_work - s.kinetic - s.strain;
      res.energies.push_back(s);
      const double mechanical = bound_kinetic + s.strain;
      // The conserved (half-step) kinetic energy cannot reveal an instability (it stays balanced
      // even while a mode grows), so the check uses the non-negative mean of the half-step
      // kinetic energies.
      const double limit =
          opt_.energy_growth_limit * (std::max(initial_bound, 0.0) + std::max(s.external_work, 0.0)) + energy_floor;
      if (!(mechanical <= limit)) {
        std::ostringstream msg;
        msg << where(n_done - 1, dt) << ": kinetic + strain energy " << mechanical << " J exceeds "
            << opt_.energy_growth_limit << " x (initial energy + external work) = " << limit
            << " J: the integration is unstable (dt = " << dt << " s)";
        throw NumericalError(msg.str());
      }
      sample_seconds += seconds_since(ts);
    }
    if (snapshot && opt_.snapshot_interval > 0 && n_done % opt_.snapshot_interval == 0) {
      const std::vector<double>& un = buf[(n_done + 1) % 3];
      const std::vector<double>& uc = buf[n_done % 3];
      std::vector<double> v(n3);
      for (int q = 0; q < n3; ++q) v[q] = (un[q] - uc[q]) / dt;
      snapshot(n_done, n_done * dt, un, v);
    }
  }
  const double loop_seconds = seconds_since(t_loop);

  const int last = opt_.steps;
  res.displacement = buf[(last + 1) % 3];
  res.velocity.assign(n3, 0.0);
  if (last == 0) {
    res.velocity = v0;
  } else {
    const std::vector<double>& before = buf[last % 3];
    for (int q = 0; q < n3; ++q) res.velocity[q] = (res.displacement[q] - before[q]) / dt;
  }

  // Quasi-static reactions at the final time: internal force minus applied load.
  fem::KernelStats st;
  elements_.compute(res.displacement.data(), 0, elements_.padded_size(), st);
  res.reactions.assign(scene_.constraints.size(), Eigen::Vector3d::Zero());
  const double t_end = res.time;
  for (const auto& d : dofs_) {
    double f[3];
    elements_.gather(d.node, f);
    double r = f[d.component] - mass_[d.node] * scene_.gravity[d.component];
    for (const auto& le : loads_)
      if (le.node == d.node) r -= scene_.loads[le.load].ramp.at(t_end) * scene_.loads[le.load].force_per_node[d.component];
    if (scene_.has_probe && scene_.probe.node == d.node) {
      const int i = d.node;
      r -= scene_.probe.stiffness * (scene_.probe.displacement[d.component] * scene_.probe.ramp.at(t_end) -
                                     res.displacement[3 * i + d.component]);
    }
    res.reactions[d.constraint][d.component] += r;
  }

  ExplicitTiming& tm = res.timing;
  tm.threads = T;
  tm.wall_seconds = loop_seconds;
  tm.steps_per_second = loop_seconds > 0 ? opt_.steps / loop_seconds : 0;
  for (const auto& s : slots) {
    for (int k = 0; k < fem::kNumElementKinds; ++k) tm.kernel_seconds[k] += s.kernel_seconds[k];
    tm.node_seconds += s.node_seconds;
  }
  for (int k = 0; k < fem::kNumElementKinds; ++k) tm.element_counts[k] = elements_.count(static_cast<fem::ElementKind>(k));
  tm.sample_seconds = sample_seconds;
  trajectories_ = nullptr;
  probe_force_ = nullptr;
  return res;
}

}  // namespace softsim::dynamics
