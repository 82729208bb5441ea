#include "softsim/regions/region_tracker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/io/errors.hpp"

namespace softsim::regions {

namespace {

void add(RegionStats& to, const RegionStats& a, const RegionStats& minus) {
  to.frames += a.frames - minus.frames;
  to.secondary_updates += a.secondary_updates - minus.secondary_updates;
  to.secondary_skipped += a.secondary_skipped - minus.secondary_skipped;
  to.secondary_seconds += a.secondary_seconds - minus.secondary_seconds;
  to.interface_seconds += a.interface_seconds - minus.interface_seconds;
  to.secondary_max_seconds = std::max(to.secondary_max_seconds, a.secondary_max_seconds);
}

void check_options(const RegionOptions& o) {
  if (!(o.radius > 0) || !std::isfinite(o.radius)) throw InputError("regions: the radius must be positive");
  const auto& a = o.adaptive;
  if (a.kind == AdaptiveRadius::Kind::fixed) return;
  if (!(a.max_radius > o.radius) || !std::isfinite(a.max_radius))
    throw InputError("regions: the adaptive max_radius must exceed the radius");
  if (a.levels < 2) throw InputError("regions: an adaptive radius needs at least 2 levels");
  if (!(a.gradient >= 0) || !(a.threshold > 0) || a.hold_frames < 0)
    throw InputError("regions: adaptive gradient >= 0, threshold > 0 and hold_frames >= 0 expected");
}

}  // namespace

RegionTracker::RegionTracker(const mesh::TetMesh& mesh, const hybrid::DhdConfig& model,
                             std::vector<fem::ElementKind> kinds, double dt, int substeps, const RegionOptions& options)
    : mesh_(&mesh), model_(model), kinds_(std::move(kinds)), dt_(dt), substeps_(substeps), options_(options),
      hold_(std::max(1, options.adaptive.hold_frames)) {
  check_options(options);
  masses_ = dynamics::lumped_mass(mesh, model.material.elastic.density);
  const int n = mesh.num_nodes();
  Eigen::VectorXd gravity = Eigen::VectorXd::Zero(3 * n);
  for (int i = 0; i < n; ++i) gravity.segment<3>(3 * i) = masses_[i] * model.scene.gravity;
  linear_ = std::make_unique<LinearModel>(
      mesh, model.material, dynamics::constrained_mask(dynamics::resolve_constraints(model.scene, n), n),
      std::move(gravity), masses_, model.damping_alpha);
  rest_.assign(3 * static_cast<std::size_t>(n), 0.0);
  const bool adaptive = options.adaptive.kind != AdaptiveRadius::Kind::fixed;
  level_frames_.assign(adaptive ? options.adaptive.levels : 1, 0);
}

double RegionTracker::level_radius(int level) const {
  const auto& a = options_.adaptive;
  if (a.kind == AdaptiveRadius::Kind::fixed) return options_.radius;
  return options_.radius + (a.max_radius - options_.radius) * level / (a.levels - 1);
}

int RegionTracker::target_level(int centre, long frame) {
  const auto& a = options_.adaptive;
  if (a.kind == AdaptiveRadius::Kind::fixed) return 0;
  const double* u = displacement();
  double r = options_.radius;
  if (a.kind == AdaptiveRadius::Kind::linear) {
    r += a.gradient * Eigen::Vector3d(u + 3 * centre).norm();  // 001 Fig. 5
  } else {
    for (std::size_t k = 0; k < near_nodes_.size(); ++k)
      if (Eigen::Vector3d(u + 3 * near_nodes_[k]).norm() > a.threshold) r = std::max(r, near_distance_[k]);
  }
  const double step = (a.max_radius - options_.radius) / (a.levels - 1);
  // Round up: the region covers at least the target radius.
  const int level = std::clamp(static_cast<int>(std::ceil((r - options_.radius) / step - 1e-9)), 0, a.levels - 1);
  // Grow at once, shrink only after the smaller size has held for hold_frames frames.
  return a.hold_frames > 0 ? hold_.push(frame, level) : level;
}

void RegionTracker::follow(const std::array<int, 3>& nodes, const Eigen::Vector3d& weights, long frame) {
  int a = 0;
  weights.maxCoeff(&a);
  const bool inside = active_ && active_->interior(nodes[0]) && active_->interior(nodes[1]) && active_->interior(nodes[2]);
  const int centre = inside ? centre_ : nodes[a];
  if (centre != centre_ && options_.adaptive.kind == AdaptiveRadius::Kind::threshold) {
    near_nodes_.clear();
    near_distance_.clear();
    const Eigen::Vector3d c = mesh_->nodes[centre];
    for (int i = 0; i < mesh_->num_nodes(); ++i) {
      const double d = (mesh_->nodes[i] - c).norm();
      if (d <= options_.adaptive.max_radius) {
        near_nodes_.push_back(i);
        near_distance_.push_back(d);
      }
    }
  }
  const int level = target_level(centre, frame);
  if (inside && level == active_level_) return;
  activate(centre, level);
}

void RegionTracker::activate(int centre, int level) {
  using Clock = std::chrono::steady_clock;
  // What the current region publishes, brought up to date, is where the next one starts: its
  // primary nodes with their previous step (the central difference resumes), the rest at rest
  // where the secondary put them (quasi-static).
  std::vector<double> u, u_before;
  if (active_) {
    active_->refresh_secondary();
    u.assign(active_->displacement(), active_->displacement() + rest_.size());
    u_before = u;
    active_->primary_previous(u_before.data());
    add(retired_, active_->stats(), active_from_);
    ++builds_.switches;
  }
  if (centre != centre_) {
    built_.clear();  // sized for another contact node
    active_ = nullptr;
    centre_ = centre;
  }
  auto& slot = built_[level];
  if (!slot) {
    const auto t0 = Clock::now();
    slot = std::make_unique<RegionSolver>(*mesh_, model_, kinds_, masses_, *linear_, dt_, substeps_,
                                          select_primary_region(*mesh_, centre, level_radius(level)), options_);
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    ++builds_.builds;
    builds_.seconds += seconds;
    builds_.max_seconds = std::max(builds_.max_seconds, seconds);
  }
  active_ = slot.get();
  active_level_ = level;
  if (!u.empty()) active_->start_from(u, u_before);
  active_from_ = active_->stats();
}

void RegionTracker::frame(const std::vector<dynamics::AppliedForce>& forces) {
  if (!active_) return;
  active_->frame(forces);
  ++level_frames_[std::max(active_level_, 0)];
}

void RegionTracker::back_to_rest() {
  for (auto& [level, r] : built_) r->start_from({}, {});
}

RegionStats RegionTracker::totals() const {
  RegionStats t = retired_;
  if (active_) add(t, active_->stats(), active_from_);
  return t;
}

}  // namespace softsim::regions
