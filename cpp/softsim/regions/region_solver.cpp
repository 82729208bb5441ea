#include "softsim/regions/region_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "softsim/hybrid/dhd_scene.hpp"
#include "softsim/io/errors.hpp"

namespace softsim::regions {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void check_supported(const hybrid::DhdConfig& model) {
  const auto& s = model.scene;
  if (!s.loads.empty()) throw InputError("regions: the model's nodal loads are not supported (the haptic loop is the input)");
  if (s.has_probe) throw InputError("regions: the model's probe spring is not supported (the haptic loop is the probe)");
  for (const auto& c : s.constraints)
    if (!c.displacement.isZero())
      throw InputError("regions: constraint \"" + c.name + "\" prescribes a non-zero displacement; regions hold constraints at zero");
}

}  // namespace

RegionSolver::RegionSolver(const mesh::TetMesh& mesh, const hybrid::DhdConfig& model,
                           const std::vector<fem::ElementKind>& kinds, const std::vector<double>& masses,
                           const LinearModel& linear, double dt, int substeps, PrimaryRegion region,
                           const RegionOptions& options)
    : mesh_(&mesh), region_(std::move(region)), options_(options), substeps_(substeps) {
  const auto t0 = Clock::now();
  check_supported(model);
  if (options.secondary_every < 1) throw InputError("regions: secondary_every must be at least 1");
  if (options.secondary_dynamic && options.coupling != Coupling::exchange)
    throw InputError("regions: an implicit-dynamic secondary needs the exchange coupling (001 eq. 7)");
  if (!(options.skip_below >= 0)) throw InputError("regions: skip_below must not be negative");
  if (options.far_field_mass && options.coupling != Coupling::condensed)
    throw InputError("regions: the far field's mass on the interface (Guyan) needs the condensed coupling");
  if (options.far_field_modes < 0) throw InputError("regions: far_field_modes must not be negative");
  if (options.far_field_modes > 0 && !options.far_field_mass)
    throw InputError("regions: the far field's modes (Craig-Bampton) need its Guyan mass on the interface");
  if (options.single_precision && options.coupling != Coupling::condensed)
    throw InputError("regions: a single-precision interface product needs the condensed coupling");
  // Gravity acts on the primary's masses and, condensed, on the far field's (h): a far-field
  // mass on the interface would carry its weight twice.
  if (options.far_field_mass && !model.scene.gravity.isZero())
    throw InputError("regions: the far field's mass on the interface (Guyan) is not combined with gravity");
  const bool exchange = options.coupling == Coupling::exchange;
  // The primary region's scene: the interface held at the published values (exchange; constraint
  // a holds interface node a), then the model's constraints on the primary nodes, which win where
  // both act (a fixed interface node stays fixed).
  scene_.gravity = model.scene.gravity;
  scene_.gravity_ramp = model.scene.gravity_ramp;
  if (exchange) {
    for (std::size_t a = 0; a < region_.interface.size(); ++a) {
      dynamics::DisplacementConstraint c;
      c.name = "interface[" + std::to_string(a) + "]";
      c.nodes = {region_.interface_local[a]};
      scene_.constraints.push_back(std::move(c));
    }
  }
  for (const auto& c : model.scene.constraints) {
    dynamics::DisplacementConstraint local = c;
    local.nodes.clear();
    for (int i : c.nodes)
      if (region_.local[i] >= 0) local.nodes.push_back(region_.local[i]);
    if (!local.nodes.empty()) scene_.constraints.push_back(std::move(local));
  }
  // The tools touch the interior nodes they list (sub-mesh numbering, ascending like the global).
  for (const auto& tool : model.scene.tools) {
    dynamics::RigidTool local = tool;
    local.nodes.clear();
    local.positions.clear();
    for (std::size_t j = 0; j < tool.nodes.size(); ++j)
      if (region_.interior[tool.nodes[j]]) {
        local.nodes.push_back(region_.local[tool.nodes[j]]);
        local.positions.push_back(tool.positions[j]);
      }
    scene_.tools.push_back(std::move(local));
  }
  std::vector<fem::ElementKind> sub_kinds;
  sub_kinds.reserve(region_.elements.size());
  for (int e : region_.elements) sub_kinds.push_back(kinds[e]);
  std::vector<double> sub_masses;
  sub_masses.reserve(region_.nodes.size());
  for (int i : region_.nodes) sub_masses.push_back(masses[i]);
  // A primary region that covers the mesh leaves no secondary region: the whole model.
  if (region_.num_secondary_elements(mesh) > 0) {
    const auto t1 = Clock::now();
    if (exchange)
      exchange_ = std::make_unique<ExchangeSecondary>(
          linear, region_, options.secondary_dynamic ? dt * substeps * options.secondary_every : 0.0);
    else
      condensed_ = std::make_unique<CondensedSecondary>(linear, region_);
    stats_.secondary_setup_seconds = seconds_since(t1);
  }
  if (condensed_ && options.single_precision) condensed_->use_single_precision();
  if (condensed_ && options.far_field_modes > 0)
    condensed_->use_modes(options.far_field_modes, dt, hybrid::explicit_options(model, dt).damping_alpha);
  if (condensed_ && options.far_field_mass) {
    // Guyan: the far field's mass rides on the interface; the model's damping α M follows it.
    const std::vector<double> extra = condensed_->interface_masses();
    for (std::size_t a = 0; a < region_.interface.size(); ++a) sub_masses[region_.interface_local[a]] += extra[a];
  }
  elements_ = std::make_unique<fem::ElementSet>(region_.submesh, sub_kinds, model.material);
  solver_ = std::make_unique<dynamics::ExplicitSolver>(*elements_, std::move(sub_masses), scene_,
                                                       hybrid::explicit_options(model, dt));
  const std::size_t ni = 3 * region_.interface.size();
  interface_before_.assign(ni, 0.0);
  interface_last_.assign(ni, 0.0);
  interface_u_.assign(ni, 0.0);
  interface_f_.assign(ni, 0.0);
  applied_.reserve(16 + region_.interface.size());
  u_.assign(3 * static_cast<std::size_t>(mesh.num_nodes()), 0.0);
  far_nodes_.assign(mesh.num_nodes(), 1);
  for (int i : region_.nodes) far_nodes_[i] = 0;
  stats_.setup_seconds = seconds_since(t0);
  start_from({}, {});
}

void RegionSolver::start_from(const std::vector<double>& u, const std::vector<double>& u_before) {
  const std::size_t n3 = 3 * static_cast<std::size_t>(mesh_->num_nodes());
  if (u.empty())
    std::fill(u_.begin(), u_.end(), 0.0);
  else
    std::copy(u.begin(), u.begin() + n3, u_.begin());
  if (u.empty() || u_before.empty()) {
    solver_->set_initial_state({}, {});
  } else {
    std::vector<double> now(3 * region_.nodes.size()), before(3 * region_.nodes.size());
    for (std::size_t k = 0; k < region_.nodes.size(); ++k)
      for (int c = 0; c < 3; ++c) {
        now[3 * k + c] = u_[3 * region_.nodes[k] + c];
        before[3 * k + c] = u_before[3 * region_.nodes[k] + c];
      }
    solver_->set_resumed_state(std::move(now), std::move(before));
  }
  solver_->reset();
  published_interface(interface_last_);
  interface_before_ = interface_last_;
  if (exchange_) {
    // The interface starts where it is (a moved region takes over its predecessor's values).
    for (std::size_t a = 0; a < region_.interface.size(); ++a)
      solver_->set_prescribed_displacement(static_cast<int>(a), Eigen::Vector3d(interface_last_.data() + 3 * a));
    exchange_->start_at(u_.data());
  }
  if (condensed_) {
    condensed_->drop_kept();  // a recovery kept for the state left behind
    condensed_->start_modes(u_.data(), u.empty() || u_before.empty() ? nullptr : u_before.data());
  }
  last_update_ = stats_.frames;
  input_at_update_.assign(u_.begin(), u_.end());
}

double RegionSolver::gravity_factor() const { return scene_.gravity_ramp.at(solver_->time()); }

void RegionSolver::frame(const std::vector<dynamics::AppliedForce>& forces) {
  applied_.clear();
  for (const auto& f : forces) {
    const int local = region_.local[f.node];
    if (local < 0 || !region_.interior[f.node])
      throw InputError("regions: a force on node " + std::to_string(f.node) + ", outside the primary region's interior");
    applied_.push_back({local, f.force});
  }
  advance_frame(applied_.size());
}

void RegionSolver::frame_with_spring(const std::array<int, 3>& nodes, const Eigen::Vector3d& weights,
                                     const Eigen::Vector3d& anchor, double k) {
  applied_.clear();
  for (int a = 0; a < 3; ++a) {
    if (region_.local[nodes[a]] < 0 || !region_.interior[nodes[a]])
      throw InputError("regions: a force on node " + std::to_string(nodes[a]) + ", outside the primary region's interior");
    spring_local_[a] = region_.local[nodes[a]];
    applied_.push_back({spring_local_[a], Eigen::Vector3d::Zero()});
  }
  spring_weights_ = weights;
  spring_anchor_ = anchor;
  spring_k_ = k;
  spring_ = true;
  try {
    advance_frame(3);
  } catch (...) {
    spring_ = false;
    throw;
  }
  spring_ = false;
}

void RegionSolver::spring_forces() {
  // x_c = Σ w_a (X_a + u_a) at this substep; the spring pulls it toward the anchor (the tip).
  const double* u = solver_->displacement();
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a)
    x += spring_weights_[a] * (region_.submesh.nodes[spring_local_[a]] + Eigen::Vector3d(u + 3 * spring_local_[a]));
  const Eigen::Vector3d f = spring_k_ * (spring_anchor_ - x);
  if (!f.allFinite()) throw NumericalError("regions: the probe spring's force is not finite");
  for (int a = 0; a < 3; ++a) applied_[a].force = spring_weights_[a] * f;
}

void RegionSolver::advance_frame(std::size_t contact_forces) {
  if (!condensed_) {
    // 001 Fig. 4: between updates the interface moves linearly from the previous update's values
    // to the last one's over `every` frames (one update late); held: the last values.
    const long since = stats_.frames - last_update_ + 1;
    const double s = options_.interpolate ? std::min(1.0, double(since) / options_.secondary_every) : 1.0;
    for (std::size_t a = 0; a < region_.interface.size(); ++a) {
      Eigen::Vector3d value;
      for (int c = 0; c < 3; ++c)
        value[c] = interface_before_[3 * a + c] + s * (interface_last_[3 * a + c] - interface_before_[3 * a + c]);
      solver_->set_prescribed_displacement(static_cast<int>(a), value);
    }
    if (!spring_) {
      solver_->set_applied_forces(applied_);
      solver_->advance(substeps_);
    } else {
      for (int k = 0; k < substeps_; ++k) {
        spring_forces();
        solver_->set_applied_forces(applied_);
        solver_->advance(1);
      }
    }
  } else {
    // The condensed secondary acts at every substep, from the interface displacement of that
    // step (000 eq. 33 evaluates every internal force at u_n).
    for (int s = 0; s < substeps_; ++s) {
      if (spring_) spring_forces();
      const double* u = solver_->displacement();
      for (std::size_t a = 0; a < region_.interface.size(); ++a)
        for (int c = 0; c < 3; ++c) interface_u_[3 * a + c] = u[3 * region_.interface_local[a] + c];
      const auto t0 = Clock::now();
      condensed_->interface_force(interface_u_.data(), gravity_factor(), interface_f_.data());
      stats_.interface_seconds += seconds_since(t0);
      applied_.resize(contact_forces);
      for (std::size_t a = 0; a < region_.interface.size(); ++a)
        applied_.push_back({region_.interface_local[a], Eigen::Vector3d(interface_f_.data() + 3 * a)});
      solver_->set_applied_forces(applied_);
      solver_->advance(1);
      condensed_->advance_modes();  // the far field's modes step with it, from the same u_I
    }
  }
  publish_primary();
  ++stats_.frames;
  if ((exchange_ || condensed_) && (stats_.frames - last_update_) >= options_.secondary_every) secondary_update();
}

bool RegionSolver::secondary_affected(const std::vector<int>& elements) const {
  if (!exchange_ && !condensed_) return false;
  for (int e : elements) {
    if (!std::binary_search(region_.elements.begin(), region_.elements.end(), e)) return true;
    if (exchange_)
      for (int n : mesh_->tets[e])
        if (region_.local[n] >= 0 && !region_.interior[n]) return true;
  }
  return false;
}

void RegionSolver::remove_primary_elements(const std::vector<int>& elements) {
  std::vector<int> local;
  for (int e : elements) {
    const auto it = std::lower_bound(region_.elements.begin(), region_.elements.end(), e);
    if (it != region_.elements.end() && *it == e) local.push_back(static_cast<int>(it - region_.elements.begin()));
  }
  if (local.empty()) return;
  const auto report = solver_->remove_elements(region_.submesh, local);  // 000's local update
  publish_primary();
  ++stats_.local_cuts;
  stats_.local_cut_seconds += report.seconds;
  stats_.local_cut_max_seconds = std::max(stats_.local_cut_max_seconds, report.seconds);
}

void RegionSolver::publish_primary() {
  const double* u = solver_->displacement();
  for (std::size_t k = 0; k < region_.nodes.size(); ++k)
    for (int c = 0; c < 3; ++c) u_[3 * region_.nodes[k] + c] = u[3 * k + c];
}

void RegionSolver::published_interface(std::vector<double>& out) const {
  for (std::size_t a = 0; a < region_.interface.size(); ++a)
    for (int c = 0; c < 3; ++c) out[3 * a + c] = u_[3 * region_.interface[a] + c];
}

void RegionSolver::primary_previous(double* u) const {
  std::vector<double> v(3 * region_.nodes.size());
  solver_->velocity(v.data());
  const double* now = solver_->displacement();
  const double dt = solver_->dt();
  for (std::size_t k = 0; k < v.size(); ++k) u[3 * region_.nodes[k / 3] + k % 3] = now[k] - dt * v[k];
}

void RegionSolver::previous_state(double* u) {
  primary_previous(u);
  if (condensed_) condensed_->recover_previous(u, gravity_factor());
}

void RegionSolver::refresh_secondary() {
  // A dynamic secondary steps only at its own rate: its last step (at most one update old) is
  // what the next region starts from.
  if ((exchange_ && !exchange_->dynamic()) || condensed_) secondary_update(true);
  recover_far_field();
}

const double* RegionSolver::displacement() const {
  recover_far_field();
  return u_.data();
}

void RegionSolver::recover_far_field() const {
  if (!condensed_ || !condensed_->recovery_kept()) return;
  const auto t0 = Clock::now();
  condensed_->recover_kept(u_.data());
  ++stats_.far_field_recoveries;
  const double s = seconds_since(t0);
  stats_.secondary_seconds += s;
  stats_.secondary_max_seconds = std::max(stats_.secondary_max_seconds, s);
}

void RegionSolver::secondary_update(bool forced) {
  // What the secondary update would see: the primary interior (exchange) or the interface
  // (condensed). Below the threshold since the last update, nothing far away needs to move.
  double moved = 0;
  const bool exchange = exchange_ != nullptr;
  for (int i : region_.nodes) {
    if (exchange != (region_.interior[i] != 0)) continue;
    for (int c = 0; c < 3; ++c) moved = std::max(moved, std::abs(u_[3 * i + c] - input_at_update_[3 * i + c]));
  }
  if (!forced && options_.skip_below > 0 && moved < options_.skip_below) {
    ++stats_.secondary_skipped;
    last_update_ = stats_.frames;
    interface_before_ = interface_last_;  // hold: the interface stays where it is
    return;
  }
  const auto t0 = Clock::now();
  for (int i : region_.nodes)
    for (int c = 0; c < 3; ++c) input_at_update_[3 * i + c] = u_[3 * i + c];
  last_update_ = stats_.frames;
  ++stats_.secondary_updates;
  if (!exchange) {
    // Condensed: the far field changes no force (pictures only): what the recovery would read
    // is kept, and the solve waits for someone to read the far field (displacement()).
    condensed_->keep_for_recovery(u_.data(), gravity_factor());
    return;
  }
  exchange_->solve(u_.data(), gravity_factor());
  interface_before_ = interface_last_;
  published_interface(interface_last_);
  const double s = seconds_since(t0);
  stats_.secondary_seconds += s;
  stats_.secondary_max_seconds = std::max(stats_.secondary_max_seconds, s);
}

}  // namespace softsim::regions
