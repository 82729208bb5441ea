#include "softsim/multirate/async_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "softsim/io/errors.hpp"

namespace softsim::multirate {

namespace {

bool same_solver(const SolverSpec& a, const SolverSpec& b) {
  if (a.kind != b.kind) return false;
  if (a.kind == SolverKind::kImplicit) return a.implicit_scheme == b.implicit_scheme;
  if (a.kind == SolverKind::kExplicit) return a.explicit_variant == b.explicit_variant;
  return true;
}

}  // namespace

AsyncSolver::AsyncSolver(const ReducedSystem& system, int contact_free_node, const AsyncSpec& spec)
    : order_(contact_distance_order(system, contact_free_node)),
      dpn_(system.dofs_per_node),
      nodes_(system.num_free_nodes()),
      frame_step_(spec.frame_step),
      policy_(spec.primary),
      adaptive_(spec.primary.adaptive()),
      interpolate_(spec.interpolate),
      held_size_(spec.primary.hold_frames + 1) {
  system_ = renumbered(system, order_);
  if (!(frame_step_ > 0)) throw InputError("asynchronous regions: the frame step must be positive");
  PrimarySizePolicy& p = policy_;
  if (!adaptive_) p.max_nodes = p.min_nodes;
  if (p.min_nodes < 1 || p.max_nodes < p.min_nodes || p.max_nodes > nodes_)
    throw InputError("asynchronous regions: primary size range [" + std::to_string(p.min_nodes) + ", " +
                     std::to_string(p.max_nodes) + "] must lie within 1.." + std::to_string(nodes_) + " free nodes");
  if (p.kind == PrimarySizePolicy::Kind::kLinear && !(p.gradient > 0 && p.scale > 0))
    throw InputError("asynchronous regions: the linear size function needs a positive gradient and scale");
  if (p.kind == PrimarySizePolicy::Kind::kThreshold && !(p.threshold > 0))
    throw InputError("asynchronous regions: the threshold must be positive");
  if (p.hold_frames < 0) throw InputError("asynchronous regions: the hold time must not be negative");

  // Region bounds in contact-distance order: the primary region may grow up to max_nodes; the
  // secondary regions follow it.
  RegionBorders borders(nodes_, p.max_nodes);
  for (std::size_t r = 0; r < spec.secondary.size(); ++r) {
    const SecondaryRegionSpec& s = spec.secondary[r];
    const std::string name = "secondary region " + std::to_string(r + 1);
    if (s.every < 1) throw InputError(name + ": `every` must be at least 1");
    if (s.nodes == 0 && r + 1 != spec.secondary.size())
      throw InputError(name + ": only the last region may take the remaining nodes");
    const int size = borders.size_of(s.nodes);
    if (!borders.fits(size))
      throw InputError(name + ": " + std::to_string(size) + " nodes do not fit after node " + std::to_string(borders.end()) +
                       " of " + std::to_string(nodes_) + " free nodes");
    borders.append(size);
  }
  if (!borders.complete())
    throw InputError("asynchronous regions: the regions cover " + std::to_string(borders.end()) + " of " +
                     std::to_string(nodes_) + " free nodes");
  const std::vector<int>& bounds = borders.bounds();

  // Leading full-rate regions with the primary's solver are part of the primary solve.
  std::size_t merged = 0;
  while (spec.merge_full_rate && merged < spec.secondary.size() && spec.secondary[merged].every == 1 &&
         same_solver(spec.secondary[merged].solver, spec.primary_solver))
    ++merged;
  if (merged > 0 && adaptive_)
    throw InputError("asynchronous regions: an adaptable primary region needs the first secondary region "
                     "to be solved less often than every frame");

  const LinearSolverKind ls = spec.linear_solver;
  const bool enforce = spec.enforce_stability_limit;
  auto make_block = [&](int begin_node, int end_node, const SolverSpec& solver, int every, const std::string& name,
                        SettingAtFault solver_setting) {
    owned_.push_back(std::make_unique<BlockIntegrator>(system_, begin_node * dpn_, end_node * dpn_, solver,
                                                       every * frame_step_, ls, enforce, name, solver_setting));
    return owned_.back().get();
  };
  const SettingAtFault primary_setting{SettingAtFault::Kind::kPrimarySolver};
  if (merged > 0) {
    primary_min_ = bounds[merged];
    primary_blocks_.push_back(make_block(0, primary_min_, spec.primary_solver, 1, "primary region", primary_setting));
  } else {
    primary_min_ = p.min_nodes;
    for (int n = p.min_nodes; n <= p.max_nodes; ++n)
      primary_blocks_.push_back(
          make_block(0, n, spec.primary_solver, 1, "primary region (" + std::to_string(n) + " nodes)", primary_setting));
  }
  region_of_node_.assign(nodes_, 0);
  for (std::size_t r = merged; r < spec.secondary.size(); ++r) {
    const SecondaryRegionSpec& s = spec.secondary[r];
    const int begin_node = bounds[r], end_node = bounds[r + 1];
    const bool follows_primary = r == merged;  // begins where the primary region ends (adapts with it)
    Secondary sec;
    sec.every = s.every;
    const std::string name = "secondary region " + std::to_string(r + 1);
    const SettingAtFault setting{SettingAtFault::Kind::kSecondarySolver, static_cast<int>(r)};
    if (follows_primary && adaptive_) {
      for (int n = p.min_nodes; n <= p.max_nodes; ++n) sec.blocks.push_back(make_block(n, end_node, s.solver, s.every, name, setting));
    } else {
      sec.blocks.push_back(make_block(begin_node, end_node, s.solver, s.every, name, setting));
    }
    for (int node = begin_node; node < end_node; ++node) region_of_node_[node] = static_cast<int>(secondary_.size());
    secondary_.push_back(std::move(sec));
  }
  if (secondary_.empty() && primary_min_ != nodes_)
    throw InputError("asynchronous regions: nodes outside the primary region need a secondary region");
  reset();
}

void AsyncSolver::reset() {
  const int n = system_.num_dofs();
  u_.setZero(n);
  v_.setZero(n);
  u_prev_.setZero(n);
  view_.setZero(n);
  force_.setZero(n);
  previous_force_.setZero(n);
  frame_ = 0;
  primary_end_ = primary_min_;
  held_size_.reset();
  for (Secondary& s : secondary_) s.last_update = 0;
}

double AsyncSolver::published(int dof, long frame) const {
  const int node = dof / dpn_;
  if (node < primary_end_ || !interpolate_) return u_[dof];
  const Secondary& s = secondary_[region_of_node_[node]];
  // 001 Fig. 4: from the previous solution to the last one over the `every` frames after it.
  const double t = std::min(1.0, static_cast<double>(frame - s.last_update) / s.every);
  return u_prev_[dof] + t * (u_[dof] - u_prev_[dof]);
}

void AsyncSolver::refresh_view(const BlockIntegrator& block, long frame) {
  for (int d = block.begin(); d < block.end(); ++d) view_[d] = u_[d];
  for (int c : block.connections()) view_[c] = published(c, frame);
}

int AsyncSolver::target_primary_size(long frame) const {
  if (policy_.kind == PrimarySizePolicy::Kind::kLinear) {
    double deformation = 0.0;
    for (int d = 0; d < dpn_; ++d) deformation += u_[d] * u_[d];
    return linear_primary_size(policy_, std::sqrt(deformation));
  }
  // Threshold: the primary region reaches the farthest node whose displacement exceeds it.
  const double limit = policy_.threshold * policy_.threshold;
  int last = -1;
  for (int node = 0; node < policy_.max_nodes; ++node) {
    double sq = 0.0;
    for (int d = 0; d < dpn_; ++d) {
      const double x = published(node * dpn_ + d, frame);
      sq += x * x;
    }
    if (sq > limit) last = node;
  }
  return std::clamp(last + 1, policy_.min_nodes, policy_.max_nodes);
}

void AsyncSolver::resize_primary(int target, long frame) {
  const Secondary& first = secondary_.front();
  if (target > primary_end_) {
    // Joining nodes start where their neighbours have been seeing them.
    for (int dof = primary_end_ * dpn_; dof < target * dpn_; ++dof) {
      const double shown = published(dof, frame);
      if (interpolate_) v_[dof] = (u_[dof] - u_prev_[dof]) / (first.every * frame_step_);
      u_[dof] = shown;
    }
  } else {
    // Leaving nodes hold their value until the first secondary region solves them.
    for (int dof = target * dpn_; dof < primary_end_ * dpn_; ++dof) u_prev_[dof] = u_[dof];
  }
  primary_end_ = target;
}

void AsyncSolver::advance(const Eigen::VectorXd& contact_force) {
  const long frame = frame_ + 1;
  if (adaptive_) {
    const int target = held_size_.push(frame, target_primary_size(frame_));
    if (target != primary_end_) resize_primary(target, frame_);
  }
  previous_force_.head(dpn_) = force_.head(dpn_);
  force_.head(dpn_) = contact_force;  // the contact node is node 0 of the renumbered system

  BlockIntegrator& primary = primary_block();
  refresh_view(primary, frame);
  if (!primary.advance(view_, force_, previous_force_, u_, v_))
    throw NumericalError("asynchronous regions: non-finite displacement in the primary region at frame " +
                         std::to_string(frame));
  for (Secondary& s : secondary_) {
    if (frame % s.every != 0) continue;
    BlockIntegrator& block = secondary_block(s);
    refresh_view(block, frame);
    if (interpolate_)
      for (int d = block.begin(); d < block.end(); ++d) u_prev_[d] = u_[d];
    if (!block.advance(view_, force_, previous_force_, u_, v_))
      throw NumericalError("asynchronous regions: non-finite displacement in " + block.name() + " at frame " +
                           std::to_string(frame));
    s.last_update = frame;
  }
  frame_ = frame;
}

void AsyncSolver::published_displacement(Eigen::VectorXd& out) const {
  out.resize(system_.num_dofs());
  for (int k = 0; k < nodes_; ++k)
    for (int d = 0; d < dpn_; ++d) out[order_[k] * dpn_ + d] = published(k * dpn_ + d, frame_);
}

double AsyncSolver::smallest_stability_limit() const {
  double limit = std::numeric_limits<double>::infinity();
  for (const auto& b : owned_) limit = std::min(limit, b->stability_limit());
  return limit;
}

}  // namespace softsim::multirate
