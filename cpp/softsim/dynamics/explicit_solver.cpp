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
  int timed_steps = 0;
};

constexpr int kTimingStride = 8;

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
  build_schedule();
}

// Parts (one per thread) are runs of tiles of about equal cost. A node is updated by the part
// owning its ready tile: right after that tile if all its elements belong to the part, after
// the mid-step barrier otherwise. Per-node lists of the scene's special entries let the owner
// do everything a node needs.
void ExplicitSolver::build_schedule() {
  const int T = opt_.threads;
  const int tiles = elements_.num_tiles();
  std::vector<double> cum(tiles + 1, 0.0);
  for (int t = 0; t < tiles; ++t) cum[t + 1] = cum[t] + elements_.tile_cost(t);
  tile_begin_.assign(T + 1, tiles);
  tile_begin_[0] = 0;
  int t = 0;
  for (int p = 1; p < T; ++p) {
    const double target = cum[tiles] * p / T;
    while (t < tiles && cum[t + 1] <= target) ++t;
    tile_begin_[p] = t;
  }
  special_.assign(n_, 0);
  for (const auto& d : dofs_) special_[d.node] = 1;
  for (const auto& l : loads_) special_[l.node] = 1;
  for (int node : opt_.trajectory_nodes) special_[node] = 1;
  if (scene_.has_probe) special_[scene_.probe.node] = 1;
  std::vector<int> part_of_tile(tiles, 0);
  for (int p = 0; p < T; ++p)
    for (int q = tile_begin_[p]; q < tile_begin_[p + 1]; ++q) part_of_tile[q] = p;
  // Each list holds the plain nodes first, then the special ones (from `split` on).
  local_begin_.assign(tiles + 1, 0);
  local_split_.assign(tiles, 0);
  local_nodes_.clear();
  std::vector<std::vector<int>> deferred(T), deferred_special(T);
  for (int q = 0; q < tiles; ++q) {
    const int p = part_of_tile[q];
    std::vector<int> plain, special;
    for (const int* it = elements_.ready_nodes_begin(q); it != elements_.ready_nodes_end(q); ++it) {
      const bool local = elements_.first_tile(*it) >= tile_begin_[p];
      (local ? (special_[*it] ? special : plain) : (special_[*it] ? deferred_special[p] : deferred[p])).push_back(*it);
    }
    local_nodes_.insert(local_nodes_.end(), plain.begin(), plain.end());
    local_split_[q] = static_cast<int>(local_nodes_.size());
    local_nodes_.insert(local_nodes_.end(), special.begin(), special.end());
    local_begin_[q + 1] = static_cast<int>(local_nodes_.size());
  }
  deferred_begin_.assign(T + 1, 0);
  deferred_split_.assign(T, 0);
  deferred_nodes_.clear();
  for (int p = 0; p < T; ++p) {
    deferred_nodes_.insert(deferred_nodes_.end(), deferred[p].begin(), deferred[p].end());
    deferred_split_[p] = static_cast<int>(deferred_nodes_.size());
    deferred_nodes_.insert(deferred_nodes_.end(), deferred_special[p].begin(), deferred_special[p].end());
    deferred_begin_[p + 1] = static_cast<int>(deferred_nodes_.size());
  }
  // Per-node lists of special entries (sorted by node already for dofs and loads).
  auto csr = [&](std::vector<int>& begin, auto node_of, int count) {
    begin.assign(n_ + 1, 0);
    for (int e = 0; e < count; ++e) ++begin[node_of(e) + 1];
    for (int i = 0; i < n_; ++i) begin[i + 1] += begin[i];
  };
  csr(dof_begin_, [&](int e) { return dofs_[e].node; }, static_cast<int>(dofs_.size()));
  csr(load_begin_, [&](int e) { return loads_[e].node; }, static_cast<int>(loads_.size()));
  trajectory_order_.resize(opt_.trajectory_nodes.size());
  for (std::size_t j = 0; j < trajectory_order_.size(); ++j) trajectory_order_[j] = static_cast<int>(j);
  std::stable_sort(trajectory_order_.begin(), trajectory_order_.end(),
                   [&](int a, int b) { return opt_.trajectory_nodes[a] < opt_.trajectory_nodes[b]; });
  csr(trajectory_begin_, [&](int j) { return opt_.trajectory_nodes[trajectory_order_[j]]; },
      static_cast<int>(trajectory_order_.size()));
}

void ExplicitSolver::set_initial_state(std::vector<double> u0, std::vector<double> v0) {
  if (!u0.empty() && static_cast<int>(u0.size()) != 3 * n_) throw std::invalid_argument("initial displacement size");
  if (!v0.empty() && static_cast<int>(v0.size()) != 3 * n_) throw std::invalid_argument("initial velocity size");
  u0_ = std::move(u0);
  v0_ = std::move(v0);
}

// Gather and central-difference update (000 eq. 33) of node i; `check` turns NaN as soon as a
// value is not finite.
template <bool kGravity>
inline void ExplicitSolver::update_node(int i, const double* up, const double* uc, double* un, double& check) const {
  double f[3];
  elements_.gather(i, f);
  const double a = A_[i], b = B_[i], c = C_[i];
  double x = b * uc[3 * i] - c * up[3 * i] - a * f[0];
  double y = b * uc[3 * i + 1] - c * up[3 * i + 1] - a * f[1];
  double z = b * uc[3 * i + 2] - c * up[3 * i + 2] - a * f[2];
  if (kGravity) {
    const double am = Am_[i];
    x += am * scene_.gravity.x();
    y += am * scene_.gravity.y();
    z += am * scene_.gravity.z();
  }
  un[3 * i] = x;
  un[3 * i + 1] = y;
  un[3 * i + 2] = z;
  check += (x - x) + (y - y) + (z - z);
}

// Nodes list[begin, split) are plain, list[split, end) special.
template <bool kGravity>
void ExplicitSolver::update_nodes(const int* list, int begin, int split, int end, int step, const double* up,
                                  const double* uc, double* un, double& check) {
  for (int k = begin; k < split; ++k) update_node<kGravity>(list[k], up, uc, un, check);
  for (int k = split; k < end; ++k) {
    update_node<kGravity>(list[k], up, uc, un, check);
    update_special(list[k], step, up, uc, un);
  }
}

void ExplicitSolver::update_nodes(const int* list, int begin, int split, int end, int step, const double* up,
                                  const double* uc, double* un, double& check) {
  if (gravity_) update_nodes<true>(list, begin, split, end, step, up, uc, un, check);
  else update_nodes<false>(list, begin, split, end, step, up, uc, un, check);
}

// Loads, probe, constraints, work booking and trajectory samples of node i, after its update.
void ExplicitSolver::update_special(int i, int step, const double* up, const double* uc, double* un) {
  const double dt = opt_.dt;
  const double t = step * dt;
  // Nodal loads: R enters eq. 33 as + A R.
  for (int e = load_begin_[i]; e < load_begin_[i + 1]; ++e) {
    const LoadEntry& le = loads_[e];
    const NodalLoad& load = scene_.loads[le.load];
    const double r = load.ramp.at(t);
    for (int k = 0; k < 3; ++k)
      if (le.free[k]) un[3 * i + k] += A_[i] * r * load.force_per_node[k];
  }
  // The probe spring pulls its node towards the tool tip.
  const bool probe_here = scene_.has_probe && scene_.probe.node == i;
  Eigen::Vector3d probe_force = Eigen::Vector3d::Zero();
  if (probe_here) {
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
  const double alpha = opt_.damping_alpha;
  for (int e = dof_begin_[i]; e < dof_begin_[i + 1]; ++e) {
    const ConstrainedDof& d = dofs_[e];
    const int q = 3 * i + d.component;
    const double value = d.value * scene_.constraints[d.constraint].ramp.at(t + dt);
    if (moving_[d.constraint]) {
      double f[3];
      elements_.gather(i, f);
      const double m = mass_[i];
      const double total =
          m * (value - 2.0 * uc[q] + up[q]) / (dt * dt) + alpha * m * (value - up[q]) / (2.0 * dt) + f[d.component];
      if (step > 0) dof_work_[e] += 0.5 * (dof_force_[e] + total) * (uc[q] - up[q]);
      dof_force_[e] = total;
    }
    un[q] = value;
  }
  if (step > 0)
    for (int e = load_begin_[i]; e < load_begin_[i + 1]; ++e) {
      const LoadEntry& le = loads_[e];
      const NodalLoad& load = scene_.loads[le.load];
      const double r = 0.5 * (load.ramp.at(t - dt) + load.ramp.at(t));
      double w = 0;
      for (int k = 0; k < 3; ++k)
        if (le.free[k]) w += r * load.force_per_node[k] * (uc[3 * i + k] - up[3 * i + k]);
      load_work_[e] += w;
    }
  if (probe_here) {
    if (step > 0)
      for (int k = 0; k < 3; ++k)
        if (probe_free_[k]) probe_work_ += 0.5 * (probe_previous_[k] + probe_force[k]) * (uc[3 * i + k] - up[3 * i + k]);
    probe_previous_ = probe_force;
  }
  if (trajectories_ && (step + 1) % opt_.trajectory_interval == 0) {
    const int sample = (step + 1) / opt_.trajectory_interval;
    for (int j = trajectory_begin_[i]; j < trajectory_begin_[i + 1]; ++j)
      (*trajectories_)[trajectory_order_[j]][sample] = Eigen::Vector3d(un[3 * i], un[3 * i + 1], un[3 * i + 2]);
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
        // Timing is sampled on one step in kTimingStride to keep clock reads out of the loop.
        const bool timed = s % kTimingStride == 0;
        if (timed) ++me.timed_steps;
        fem::KernelStats st;
        double check = 0.0;
        for (int p = tid; p < T; p += nthreads)
          for (int q = tile_begin_[p]; q < tile_begin_[p + 1]; ++q) {
            elements_.compute_tile(uc, q, st, timed ? me.kernel_seconds.data() : nullptr);
            const auto t0 = timed ? Clock::now() : Clock::time_point();
            update_nodes(local_nodes_.data(), local_begin_[q], local_split_[q], local_begin_[q + 1], s, up, uc, un, check);
            if (timed) me.node_seconds += seconds_since(t0);
          }
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
        const auto t0 = timed ? Clock::now() : Clock::time_point();
        for (int p = tid; p < T; p += nthreads)
          update_nodes(deferred_nodes_.data(), deferred_begin_[p], deferred_split_[p], deferred_begin_[p + 1], s, up,
                       uc, un, check);
        if (timed) me.node_seconds += seconds_since(t0);
        me.bad = !(check == 0.0);
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
  // Sampled timings scaled to all steps.
  int timed = 0;
  for (const auto& s : slots) timed = std::max(timed, s.timed_steps);
  const double scale = timed > 0 ? static_cast<double>(opt_.steps) / timed : 0.0;
  for (const auto& s : slots) {
    for (int k = 0; k < fem::kNumElementKinds; ++k) tm.kernel_seconds[k] += scale * s.kernel_seconds[k];
    tm.node_seconds += scale * s.node_seconds;
  }
  for (int k = 0; k < fem::kNumElementKinds; ++k) tm.element_counts[k] = elements_.count(static_cast<fem::ElementKind>(k));
  tm.sample_seconds = sample_seconds;
  trajectories_ = nullptr;
  probe_force_ = nullptr;
  return res;
}

}  // namespace softsim::dynamics
