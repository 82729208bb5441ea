#include "softsim/regions/region_tracker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "softsim/cutting/live_mesh.hpp"
#include "softsim/cutting/pieces.hpp"
#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/io/errors.hpp"

namespace softsim::regions {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void add(RegionStats& to, const RegionStats& a, const RegionStats& minus) {
  to.frames += a.frames - minus.frames;
  to.secondary_updates += a.secondary_updates - minus.secondary_updates;
  to.secondary_skipped += a.secondary_skipped - minus.secondary_skipped;
  to.secondary_seconds += a.secondary_seconds - minus.secondary_seconds;
  to.interface_seconds += a.interface_seconds - minus.interface_seconds;
  to.secondary_max_seconds = std::max(to.secondary_max_seconds, a.secondary_max_seconds);
  to.local_cuts += a.local_cuts - minus.local_cuts;
  to.local_cut_seconds += a.local_cut_seconds - minus.local_cut_seconds;
  to.local_cut_max_seconds = std::max(to.local_cut_max_seconds, a.local_cut_max_seconds);
  to.far_field_recoveries += a.far_field_recoveries - minus.far_field_recoveries;
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
  removed_.assign(mesh.num_tets(), 0);
  rest_.assign(3 * static_cast<std::size_t>(mesh.num_nodes()), 0.0);
  update_linear();
  const bool adaptive = options.adaptive.kind != AdaptiveRadius::Kind::fixed;
  level_frames_.assign(adaptive ? options.adaptive.levels : 1, 0);
}

namespace {

struct LinearState {
  std::vector<double> masses;
  std::shared_ptr<LinearModel> linear;
};

// The small-strain model and lumped masses of the mesh a cut left (reads only its arguments:
// the worker thread calls it too).
LinearState linear_state(const mesh::TetMesh& mesh, const hybrid::DhdConfig& model,
                         const std::vector<fem::ElementKind>& kinds, const std::vector<char>& removed) {
  const int n = mesh.num_nodes();
  LinearState st;
  // The mesh a cut left: its lumped masses, and its nodes without elements held (they carry no
  // stiffness; a quasi-static secondary would be singular there).
  const cutting::LiveMesh left = cutting::live_mesh(mesh, kinds, [&](int e) { return removed[e] != 0; });
  st.masses = dynamics::lumped_mass(left.mesh, model.material.elastic.density);
  std::vector<char> constrained = dynamics::constrained_mask(dynamics::resolve_constraints(model.scene, n), n);
  for (int i = 0; i < n; ++i)
    if (st.masses[i] == 0) constrained[3 * i] = constrained[3 * i + 1] = constrained[3 * i + 2] = 1;
  const bool cut = std::find(removed.begin(), removed.end(), 1) != removed.end();
  if (cut) {
    // A piece the cut detached is held by nothing: quasi-statically it has no position, and the
    // secondary's system would be singular. The linear model holds it at rest (the explicit
    // primary region still moves whatever of it lies there).
    std::vector<char> held(n, 0);
    for (const auto& c : model.scene.constraints)
      for (int i : c.nodes) held[i] = 1;
    const cutting::Pieces pieces =
        cutting::find_pieces(mesh, [&](int e) { return removed[e] != 0; }, [&](int i) { return held[i] != 0; });
    std::vector<char> loose(pieces.count, 0);
    for (int k : pieces.loose) loose[k] = 1;
    for (int i = 0; i < n; ++i)
      if (pieces.node_piece[i] >= 0 && loose[pieces.node_piece[i]])
        constrained[3 * i] = constrained[3 * i + 1] = constrained[3 * i + 2] = 1;
  }
  Eigen::VectorXd gravity = Eigen::VectorXd::Zero(3 * n);
  for (int i = 0; i < n; ++i) gravity.segment<3>(3 * i) = st.masses[i] * model.scene.gravity;
  st.linear = std::make_shared<LinearModel>(mesh, model.material, std::move(constrained), std::move(gravity),
                                            st.masses, model.damping_alpha, cut ? removed : std::vector<char>());
  return st;
}

}  // namespace

void RegionTracker::update_linear() {
  LinearState st = linear_state(*mesh_, model_, kinds_, removed_);
  masses_ = std::move(st.masses);
  linear_ = std::move(st.linear);
  linear_stale_ = false;
}

double RegionTracker::level_radius(int level) const {
  // Adaptive: `levels` sizes from radius to max_radius; beyond them (a tool's contact set that
  // needs more) the same steps go on. Fixed: steps of half the radius.
  const auto& a = options_.adaptive;
  const double step = a.kind == AdaptiveRadius::Kind::fixed ? 0.5 * options_.radius
                                                             : (a.max_radius - options_.radius) / (a.levels - 1);
  return options_.radius + step * level;
}

int RegionTracker::covering_level(int centre, const std::vector<int>& nodes) const {
  double r = 0;
  for (int i : nodes) r = std::max(r, (mesh_->nodes[i] - mesh_->nodes[centre]).norm());
  if (r <= options_.radius) return 0;
  const double step = level_radius(1) - level_radius(0);
  // Rounded up, with room for the rounding of level_radius: the region's radius reaches r.
  return static_cast<int>(std::ceil((r - options_.radius) / step + 1e-9));
}

int RegionTracker::target_level(int centre, long frame) {
  const auto& a = options_.adaptive;
  if (a.kind == AdaptiveRadius::Kind::fixed) return 0;
  // The linear policy reads the centre node: a primary node's published value is current; the
  // threshold policy reads nodes out to max_radius, the far field's among them.
  const bool centre_primary = active_ && !active_->far_nodes()[centre];
  const double* u = a.kind == AdaptiveRadius::Kind::linear && centre_primary ? published() : displacement();
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

void RegionTracker::set_centre(int centre) {
  if (centre == near_centre_ || options_.adaptive.kind != AdaptiveRadius::Kind::threshold) return;
  near_centre_ = centre;
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

void RegionTracker::follow(const std::array<int, 3>& nodes, const Eigen::Vector3d& weights, long frame) {
  int a = 0;
  weights.maxCoeff(&a);
  contact_node_ = nodes[a];
  const bool inside = active_ && active_->interior(nodes[0]) && active_->interior(nodes[1]) && active_->interior(nodes[2]);
  const int centre = inside ? centre_ : nodes[a];
  set_centre(centre);
  const int level = target_level(centre, frame);
  const bool background = options_.build_in_background;
  if (inside && level == active_level_) {
    // Background: the next region is asked for while the contact is still well inside this one.
    const double r = active_->region().radius;
    if (background && !building() &&
        (mesh_->nodes[nodes[a]] - mesh_->nodes[centre_]).norm() > options_.prefetch_fraction * r)
      request(nodes[a], level, frame, false);
    return;
  }
  // A region already built for this centre is made active at once (no build); otherwise it is
  // built here (inline) or asked of the worker while the current region answers (background).
  const bool cached = centre == centre_ && built_.count(level) && built_.at(level).solver;
  if (!background || cached) {
    activate(centre, level);
    return;
  }
  request(centre, level, frame, false);
}

void RegionTracker::cover(const std::vector<int>& nodes, long frame) {
  if (nodes.empty()) return;
  bool inside = active_ != nullptr;
  for (int i : nodes) inside = inside && active_->interior(i);
  int centre = centre_;
  if (!inside) {
    // Re-centred on the node of the set nearest its centroid (reference positions).
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int i : nodes) mean += mesh_->nodes[i];
    mean /= double(nodes.size());
    double best = 1e300;
    for (int i : nodes)
      if ((mesh_->nodes[i] - mean).norm() < best) {
        best = (mesh_->nodes[i] - mean).norm();
        centre = i;
      }
  }
  set_centre(centre);
  const int target = target_level(centre, frame);
  const int level = std::max(target, covering_level(centre, nodes));
  // A region that already holds the nodes is kept unless the adaptive policy changes its size.
  if (inside && (level == active_level_ || (level > active_level_ && target <= active_level_))) return;
  activate(centre, level);
  ++builds_.tool_covers;
}

int RegionTracker::count_late_contacts(const std::vector<int>& touched) {
  int late = 0;
  for (int i : touched) late += (!active_ || !active_->interior(i)) ? 1 : 0;
  builds_.late_contacts += late;
  return late;
}

std::unique_ptr<RegionSolver> RegionTracker::build(int centre, int level, double& seconds) {
  const auto t0 = Clock::now();
  if (linear_stale_) update_linear();
  auto solver = std::make_unique<RegionSolver>(*mesh_, model_, kinds_, masses_, *linear_, dt_, substeps_,
                                               select_primary_region(*mesh_, centre, level_radius(level), &removed_),
                                               options_);
  seconds = seconds_since(t0);
  return solver;
}

void RegionTracker::activate(int centre, int level) {
  // What the current region publishes, brought up to date, is where the next one starts: its
  // primary nodes with their previous step (the central difference resumes), the rest at rest
  // where the secondary put them (quasi-static).
  std::vector<double> u, u_before;
  if (active_) {
    published_state(u, u_before);
    add(retired_, active_->stats(), active_from_);
    ++builds_.switches;
    if (active_stale_) {  // its far field predates a cut: never to be used again
      built_.erase(active_level_);
      active_ = nullptr;
      active_stale_ = false;
    }
  }
  if (centre != centre_) {
    built_.clear();  // sized for another contact node
    active_ = nullptr;
    centre_ = centre;
  }
  auto& slot = built_[level];
  if (!slot.solver) {
    double seconds = 0;
    slot.solver = build(centre, level, seconds);
    slot.linear = linear_;
    ++builds_.builds;
    builds_.seconds += seconds;
    builds_.max_seconds = std::max(builds_.max_seconds, seconds);
  }
  active_ = slot.solver.get();
  active_level_ = level;
  if (level >= static_cast<int>(level_frames_.size())) level_frames_.resize(level + 1, 0);
  if (!u.empty()) active_->start_from(u, u_before);
  active_from_ = active_->stats();
}

RegionTracker::~RegionTracker() {
  if (pending_.valid()) pending_.wait();
}

void RegionTracker::request(int centre, int level, long frame, bool for_cut) {
  if (pending_.valid()) return;
  pending_centre_ = centre;
  pending_level_ = level;
  pending_frame_ = frame;
  // The worker reads the mesh, the config, the element kinds (none of which a removal changes)
  // and copies of what the frames change (the removed elements, the linear model's handle).
  std::shared_ptr<LinearModel> linear = linear_stale_ ? nullptr : linear_;
  std::vector<double> masses = linear_stale_ ? std::vector<double>() : masses_;
  std::vector<char> removed = removed_;
  const double radius = level_radius(level);
  const long generation = generation_;
  pending_ = std::async(std::launch::async, [this, centre, level, for_cut, radius, generation,
                                             linear = std::move(linear), masses = std::move(masses),
                                             removed = std::move(removed)]() mutable {
    const auto t0 = Clock::now();
    Finished done;
    done.centre = centre;
    done.level = level;
    done.generation = generation;
    done.for_cut = for_cut;
    if (!linear) {
      LinearState st = linear_state(*mesh_, model_, kinds_, removed);
      done.masses = std::move(st.masses);
      done.linear = std::move(st.linear);
    } else {
      done.linear = std::move(linear);
      done.masses = std::move(masses);
    }
    done.solver = std::make_unique<RegionSolver>(*mesh_, model_, kinds_, done.masses, *done.linear, dt_, substeps_,
                                                 select_primary_region(*mesh_, centre, radius, &removed), options_);
    done.secondary_seconds = done.solver->stats().secondary_setup_seconds;
    done.seconds = seconds_since(t0);
    return done;
  });
  if (options_.swap_after_frames == 0) take_finished();  // due in the frame that asked
}

void RegionTracker::finish_building() {
  if (pending_.valid()) take_finished();
}

void RegionTracker::between_frames(long frame) {
  if (pending_.valid()) {
    const bool due = options_.swap_after_frames >= 0 && frame >= pending_frame_ + options_.swap_after_frames;
    if (due || pending_.wait_for(std::chrono::seconds(0)) == std::future_status::ready)
      take_finished();
    else
      ++builds_.frames_while_building;
  }
  // A cut reached the active region's far field and nothing is on its way for it: ask now, around
  // the contact's node if it has moved on far enough to want a region of its own (one build
  // serves both), else where the region is.
  if (active_stale_ && !pending_.valid() && active_) {
    const bool moved = options_.build_in_background && contact_node_ >= 0 &&
                       (mesh_->nodes[contact_node_] - mesh_->nodes[centre_]).norm() >
                           options_.prefetch_fraction * active_->region().radius;
    request(moved ? contact_node_ : centre_, active_level_, frame, true);
  }
}

void RegionTracker::take_finished() {
  const auto t0 = Clock::now();
  pending_.wait();
  const double waited = seconds_since(t0);
  builds_.wait_seconds += waited;
  builds_.wait_max_seconds = std::max(builds_.wait_max_seconds, waited);
  Finished done = pending_.get();  // a numerical failure of the build is thrown here, in a frame
  if (done.generation != generation_) {
    ++builds_.discarded;  // a cut came after it was asked for: built again when needed
    return;
  }
  swap_in(std::move(done));
}

void RegionTracker::published_state(std::vector<double>& u, std::vector<double>& u_before, std::size_t n3) {
  if (n3 == 0) n3 = rest_.size();
  active_->refresh_secondary();
  u.assign(active_->displacement(), active_->displacement() + n3);
  u_before = u;
  active_->previous_state(u_before.data());
}

void RegionTracker::swap_in(Finished&& done) {
  const auto t0 = Clock::now();
  std::vector<double> u, u_before;  // a swap is an event, not a frame's work: it may allocate
  if (active_) {
    published_state(u, u_before);
    add(retired_, active_->stats(), active_from_);
    ++builds_.switches;
  }
  if (done.masses.size() && done.linear != linear_) {
    // Built on the cut mesh's linear model: it is the current one from now on.
    linear_ = done.linear;
    masses_ = std::move(done.masses);
    linear_stale_ = false;
  }
  if (done.centre != centre_) {
    built_.clear();
    centre_ = done.centre;
  }
  Built& slot = built_[done.level];
  slot.solver = std::move(done.solver);
  slot.linear = done.linear;
  active_ = slot.solver.get();
  active_level_ = done.level;
  if (done.level >= static_cast<int>(level_frames_.size())) level_frames_.resize(done.level + 1, 0);
  if (!u.empty()) active_->start_from(u, u_before);
  active_from_ = active_->stats();
  ++builds_.builds;
  ++builds_.background_builds;
  builds_.seconds += done.seconds;
  builds_.max_seconds = std::max(builds_.max_seconds, done.seconds);
  if (done.for_cut) {
    active_stale_ = false;
    ++topology_.rebuilds;
    topology_.rebuild_seconds += done.seconds;
    topology_.rebuild_max_seconds = std::max(topology_.rebuild_max_seconds, done.seconds);
    topology_.secondary_seconds += done.secondary_seconds;
    topology_.secondary_max_seconds = std::max(topology_.secondary_max_seconds, done.secondary_seconds);
  }
  ++builds_.swaps;
  const double s = seconds_since(t0);
  builds_.swap_seconds += s;
  builds_.swap_max_seconds = std::max(builds_.swap_max_seconds, s);
}

void RegionTracker::topology_changed(const TopologyChange& change) {
  if (change.empty()) return;
  ++topology_.changes;
  ++generation_;  // a build in flight was asked for on the mesh before this change
  for (int e : change.removed) removed_[e] = 1;
  linear_stale_ = true;  // regions built from now on see the cut mesh
  const bool removal_only = change.changed.empty() && change.copies.empty();
  // A separation adds node copies: the state grows to the cut mesh's nodes.
  const std::size_t n3_before = rest_.size();
  rest_.resize(3 * static_cast<std::size_t>(mesh_->num_nodes()), 0.0);
  for (auto it = built_.begin(); it != built_.end();) {
    RegionSolver* r = it->second.solver.get();
    if (removal_only && !r->secondary_affected(change.removed)) {
      // Inside the primary region: the explicit engine's local update, nothing set up again.
      const double before = r->stats().local_cut_seconds;
      r->remove_primary_elements(change.removed);
      if (r == active_) {
        const double s = r->stats().local_cut_seconds - before;
        ++topology_.local_updates;
        topology_.local_seconds += s;
        topology_.local_max_seconds = std::max(topology_.local_max_seconds, s);
      }
      ++it;
      continue;
    }
    if (r != active_) {  // a cached region the change reached: built again if it is needed again
      ++topology_.invalidated;
      it = built_.erase(it);
      continue;
    }
    if (options_.build_in_background && removal_only) {
      // The worker builds the successor on the cut mesh; meanwhile this region answers with the
      // cut made in its primary engine and its far field as before the cut (stiffer by what
      // the cut took out of it there), and the next frame boundary asks for the successor.
      r->remove_primary_elements(change.removed);
      active_stale_ = true;
      ++it;
      continue;
    }
    // The active region's secondary factorisation (and condensed interface) no longer holds:
    // the region is built anew on the cut mesh and resumes from the state it published.
    // Brought up to date first: a far field recovered rarely (a large secondary_every) would
    // otherwise hand its successor a stale far field and modes (a transient after the cut).
    std::vector<double> u, u_before;
    published_state(u, u_before, n3_before);
    // Each node copy starts from its node's state (a separation keeps every velocity).
    u.resize(rest_.size(), 0.0);
    u_before.resize(rest_.size(), 0.0);
    for (const auto& [node, copy] : change.copies)
      for (int k = 0; k < 3; ++k) {
        u[3 * copy + k] = u[3 * node + k];
        u_before[3 * copy + k] = u_before[3 * node + k];
      }
    const auto t0 = Clock::now();
    update_linear();
    const double linear_seconds = seconds_since(t0);
    double build_seconds = 0;
    auto rebuilt = build(centre_, active_level_, build_seconds);  // may fail: the old region stays
    add(retired_, active_->stats(), active_from_);
    it->second.solver = std::move(rebuilt);
    it->second.linear = linear_;
    active_ = it->second.solver.get();
    active_->start_from(u, u_before);
    active_from_ = active_->stats();
    const double total = linear_seconds + build_seconds;
    const double secondary = active_->stats().secondary_setup_seconds;
    ++topology_.rebuilds;
    topology_.rebuild_seconds += total;
    topology_.rebuild_max_seconds = std::max(topology_.rebuild_max_seconds, total);
    topology_.secondary_seconds += secondary;
    topology_.secondary_max_seconds = std::max(topology_.secondary_max_seconds, secondary);
    topology_.linear_seconds += linear_seconds;
    ++it;
  }
}

void RegionTracker::frame(const std::vector<dynamics::AppliedForce>& forces) {
  if (!active_) return;
  active_->frame(forces);
  ++level_frames_[std::max(active_level_, 0)];
}

void RegionTracker::frame_with_spring(const std::array<int, 3>& nodes, const Eigen::Vector3d& weights,
                                      const Eigen::Vector3d& anchor, double k) {
  if (!active_) return;
  active_->frame_with_spring(nodes, weights, anchor, k);
  ++level_frames_[std::max(active_level_, 0)];
}

void RegionTracker::frame_with_tool(int k, const Eigen::Vector3d& centre) {
  if (!active_) return;
  active_->set_tool_position(k, centre);
  frame({});
}

void RegionTracker::back_to_rest() {
  for (auto& [level, r] : built_) r.solver->start_from({}, {});
}

RegionStats RegionTracker::totals() const {
  RegionStats t = retired_;
  if (active_) add(t, active_->stats(), active_from_);
  return t;
}

}  // namespace softsim::regions
