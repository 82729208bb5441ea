#include "softsim/haptic/haptic_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/dynamics/spectral_step.hpp"
#include "softsim/dynamics/stable_step.hpp"
#include "softsim/hybrid/partition.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/regions/tool_cover.hpp"

namespace softsim::haptic {

FrameSubsteps frame_substeps(double frame_step, double dt_limit) {
  if (!(frame_step > 0) || !(dt_limit > 0)) throw InputError("haptic: frame step and step limit must be positive");
  const double n = std::ceil(frame_step / dt_limit * (1 - 1e-12));
  if (n > 1e7) throw InputError("haptic: a frame needs more than 10^7 explicit substeps (frame step / critical step)");
  FrameSubsteps s;
  s.substeps = std::max(1, static_cast<int>(n));
  s.dt = frame_step / s.substeps;
  return s;
}

namespace {

// SpringCoupling::substep: the spring is part of the explicit step, and adds k/m to the squared
// frequency of a node of mass m it pulls (w = 1 at worst): the step for ω² + k/m_min is
// 2/sqrt(ω² + k/m_min), i.e. 1/Δt² = 1/Δt_tissue² + 1/Δt_spring² with Δt_spring = 2 sqrt(m_min/k).
double with_spring(double tissue_dt, const mesh::TetMesh& mesh, double density, double safety, double k) {
  double m_min = 0;
  for (double m : dynamics::lumped_mass(mesh, density))
    if (m > 0 && (m_min == 0 || m < m_min)) m_min = m;
  if (!(m_min > 0)) return tissue_dt;
  const double spring_dt = safety * 2.0 * std::sqrt(m_min / k);
  return 1.0 / std::sqrt(1.0 / (tissue_dt * tissue_dt) + 1.0 / (spring_dt * spring_dt));
}

hybrid::DhdConfig with_frame_step(hybrid::DhdConfig c, const mesh::TetMesh& mesh, double frame_step,
                                  double substep_spring = 0) {
  if (c.static_solver) throw InputError("haptic: the model's solver must be explicit (solver.kind \"explicit\")");
  double limit = 0;
  if (c.explicit_solver.dt) {
    limit = *c.explicit_solver.dt;
  } else {
    auto critical = dynamics::critical_time_step(mesh, c.material.elastic);
    if (c.explicit_solver.critical_step == hybrid::CriticalStepMethod::power_iteration)  // 2/ω_max at rest
      critical.dt = dynamics::power_iteration_step(mesh, hybrid::make_partition(mesh, c.partition), c.material, c.scene).dt;
    limit = dynamics::choose_time_step(critical, std::nullopt, c.explicit_solver.safety_factor, false).dt;
  }
  if (substep_spring > 0)
    limit = with_spring(limit, mesh, c.material.elastic.density, c.explicit_solver.safety_factor, substep_spring);
  c.explicit_solver.dt = frame_substeps(frame_step, limit).dt;
  return c;
}

}  // namespace

HapticScene::HapticScene(std::shared_ptr<const mesh::TetMesh> mesh, hybrid::DhdConfig model,
                         const HapticOptions& options)
    : mesh_(mesh), options_(options) {
  if (!(options.frame_step > 0)) throw InputError("haptic: frame step must be positive");
  if (options.contact != ContactMode::tool && !(options.probe_stiffness > 0))
    throw InputError("haptic: probe stiffness must be positive");
  if (options.contact == ContactMode::tool && model.scene.tools.empty())
    throw InputError("haptic: contact \"tool\" needs a rigid tool in the model (boundary.tools)");
  const bool substep_spring = options.spring_coupling == SpringCoupling::substep && options.contact != ContactMode::tool;
  hybrid::DhdConfig c =
      with_frame_step(std::move(model), *mesh, options.frame_step, substep_spring ? options.probe_stiffness : 0.0);
  substeps_ = frame_substeps(options.frame_step, *c.explicit_solver.dt).substeps;
  if (options_.blade_mode == hybrid::CutMode::separate && !c.separates)
    throw InputError("haptic: a separating blade needs a model set up for separation (DhdConfig::separates)");
  // The contact surface follows one kind of cut: removal uncovers faces, separation adds sides.
  if (c.separates) {
    bool removes = options_.blade && options_.blade_mode == hybrid::CutMode::remove;
    for (const auto& cut : c.cuts) removes = removes || cut.mode == hybrid::CutMode::remove;
    if (removes) throw InputError("haptic: cuts that separate and cuts that remove cannot be mixed in one scene");
  }
  model_ = std::make_unique<hybrid::DhdScene>(mesh, std::move(c));
  surface_.emplace(model_->mesh());
  applied_.resize(3);
  {
    Eigen::Vector3d lo = mesh->nodes[0], hi = mesh->nodes[0];
    for (const auto& x : mesh->nodes) {
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
    runaway_distance_ = (hi - lo).norm();
  }
  if (options_.use_regions) {
    // The regions drive one rigid tool, the probe's: another would move on its own ramp in a
    // region placed for the probe.
    const auto& tools = model_->config().scene.tools;
    if (!tools.empty() && (options_.contact != ContactMode::tool || tools.size() > 1))
      throw InputError("haptic: regions take one rigid tool, driven by the probe (contact \"tool\")");
    if (options_.contact == ContactMode::tool && !(tool_margin() >= 0 && std::isfinite(tool_margin())))
      throw InputError("haptic: the regions' tool margin must be a finite distance >= 0");
    // On the model's mesh: a separating cut adds node copies to it, which the regions then take.
    regions_ = std::make_unique<regions::RegionTracker>(model_->mesh(), model_->config(), model_->kinds(), model_->dt(),
                                                        substeps_, options_.regions);
  }
  reset();
}

const double* HapticScene::displacement() const {
  if (!options_.use_regions) return model_->displacement();
  return regions_->displacement();
}

void HapticScene::prepare(const Eigen::Vector3d& probe) {
  if (!options_.use_regions || regions_->active()) return;
  if (!probe.allFinite()) throw InputError("haptic: probe position is not finite");
  const SurfacePoint s = surface_->closest(probe, displacement());
  regions_->follow(s.nodes, s.weights, frames_);
  regions_->finish_building();  // before the frames: a region built beside them is waited for here
}

void HapticScene::reset() {
  back_to_rest();
  frames_ = 0;
  model_time_ = 0;
  events_.clear();
}

void HapticScene::back_to_rest() {
  model_->reset();  // cuts are permanent: the model returns to rest with its cut mesh
  if (regions_) regions_->back_to_rest();
  in_contact_ = false;
  tool_touching_ = false;
  contact_ = SurfacePoint();
  contact_held_ = false;
  has_previous_tip_ = false;
}

double HapticScene::tool_margin() const {
  return options_.tool_margin < 0 ? 0.25 * options_.regions.radius : options_.tool_margin;
}

hybrid::DhdScene::CutEvent HapticScene::cut(const cutting::BladeSweep& sweep, hybrid::CutMode mode) {
  if (regions_ && mode == hybrid::CutMode::separate) regions_->finish_building();  // the cut changes the mesh
  const auto ev = model_->cut(sweep, mode, regions_ ? displacement() : nullptr);
  follow_cuts();
  return ev;
}

void HapticScene::scheduled_cuts() {
  const auto& cuts = model_->config().cuts;
  for (; next_scheduled_cut_ < cuts.size() && cuts[next_scheduled_cut_].time <= frames_ * options_.frame_step;
       ++next_scheduled_cut_)
    cut(cuts[next_scheduled_cut_].sweep, cuts[next_scheduled_cut_].mode);
}

Eigen::Vector3d HapticScene::tool_frame_with_regions(const Eigen::Vector3d& centre) {
  const dynamics::RigidTool& tool = model_->config().scene.tools[0];
  // Every node the tool touches or may touch before the next check is interior to the primary
  // region (the tool's contact is computed there only).
  regions::tool_nodes_within(tool, centre, displacement(), tool_margin(), tool_nodes_);
  regions_->cover(tool_nodes_, frames_);
  regions_->frame_with_tool(0, centre);
  // A node inside the tool now but outside the interior had no contact this frame: counted, and
  // the next frame's cover takes it in.
  regions::tool_nodes_within(tool, centre, displacement(), 0.0, tool_nodes_);
  regions_->count_late_contacts(tool_nodes_);
  tool_touching_ = regions_->tool_contacts(0) > 0;
  return regions_->tool_force(0);
}

void HapticScene::cut_with_blade(const Eigen::Vector3d& probe) {
  if (options_.blade && has_previous_tip_) {
    cutting::BladeSweep sweep;
    const Eigen::Vector3d half = 0.5 * options_.blade_edge;
    sweep.a0 = previous_tip_ - half;
    sweep.b0 = previous_tip_ + half;
    sweep.a1 = probe - half;
    sweep.b1 = probe + half;
    // A tool at rest, or moving along its own edge, sweeps no area: nothing to cut this frame.
    if (cutting::sweep_problem(sweep).empty()) {
      if (regions_ && options_.blade_mode == hybrid::CutMode::separate) regions_->finish_building();
      const auto ev = model_->cut(sweep, options_.blade_mode, regions_ ? displacement() : nullptr);
      const double seconds = ev.search_seconds + ev.report.seconds + ev.separation_seconds + ev.pieces_seconds;
      ++blade_stats_.sweeps;
      blade_stats_.seconds += seconds;
      blade_stats_.max_seconds = std::max(blade_stats_.max_seconds, seconds);
    }
  }
  previous_tip_ = probe;
  has_previous_tip_ = true;
  follow_cuts();
}

void HapticScene::follow_cuts() {
  const auto& events = model_->cut_events();
  // Counted before the regions react: a rebuild that fails (a numerical event) is not retried.
  while (cuts_seen_ < events.size()) {
    const auto& ev = events[cuts_seen_++];
    cut_times_.push_back(regions_ ? model_time_ : ev.time);
    if (ev.mode == hybrid::CutMode::separate) {
      surface_->follow_separation(ev.boundary);
      // Node copies change every region's mesh: the active one is built again on the cut mesh.
      if (regions_) regions_->topology_changed({{}, ev.moved_elements, ev.copies});
      continue;
    }
    const auto& gone = ev.report.elements;
    surface_->remove_elements(gone, [this](int e) { return model_->removed(e); });
    if (regions_) regions_->topology_changed({gone, {}});
  }
  if (in_contact_ && !surface_->live(contact_.triangle)) {
    in_contact_ = false;
    contact_ = SurfacePoint();
  }
}

const double* HapticScene::contact_reading(const std::array<int, 3>& nodes) const {
  if (!regions_) return model_->displacement();
  const std::vector<char>* far = regions_->far_nodes();
  if (far && !(*far)[nodes[0]] && !(*far)[nodes[1]] && !(*far)[nodes[2]]) return regions_->published();
  return regions_->displacement();
}

void HapticScene::whole_model_spring_frame(const Eigen::Vector3d& probe) {
  const double k = options_.probe_stiffness;
  const auto& X = model_->mesh().nodes;
  for (int s = 0; s < substeps_; ++s) {
    // x_c at this substep's displacement: the spring is part of the explicit step (000 eq. 33
    // evaluates every force at u_n).
    const double* u = model_->displacement();
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int a = 0; a < 3; ++a) {
      const int i = contact_.nodes[a];
      x += contact_.weights[a] * (X[i] + Eigen::Vector3d(u + 3 * i));
    }
    const Eigen::Vector3d f = k * (probe - x);
    if (!f.allFinite()) throw NumericalError("haptic: the probe spring's force is not finite");
    for (int a = 0; a < 3; ++a) applied_[a] = {contact_.nodes[a], contact_.weights[a] * f};
    model_->solver().set_applied_forces(applied_);
    model_->step(1);
  }
}

void HapticScene::update_contact(const Eigen::Vector3d& probe) {
  if (in_contact_) {
    // Attached: the same material point wherever the tip goes; else the closest point (frictionless).
    if (options_.contact == ContactMode::attach) {
      contact_ = surface_->at(contact_.triangle, contact_.weights, contact_reading(contact_.nodes));
      return;
    }
    const std::vector<char>* far = regions_ ? regions_->far_nodes() : nullptr;
    if (!far) {
      contact_ = surface_->closest_near(probe, displacement(), contact_);
      return;
    }
    // The walk reads the published displacement; one that reached the far field walks again in
    // the far field brought up to date, so it answers as if the far field were always current.
    bool read_older = false;
    const SurfacePoint s = surface_->closest_near(probe, regions_->published(), contact_, *far, read_older);
    contact_ = read_older ? surface_->closest_near(probe, displacement(), contact_) : s;
    return;
  }
  const SurfacePoint s = surface_->closest(probe, displacement());
  // Grasp, attach: the first frame takes hold; push: only a tip at or below the surface touches it.
  if (options_.contact != ContactMode::push || (probe - s.position).dot(s.normal) <= 0) {
    in_contact_ = true;
    contact_ = s;
  }
}

Eigen::Vector3d HapticScene::frame(const Eigen::Vector3d& probe) {
  ++frames_;
  if (!probe.allFinite()) throw InputError("haptic: probe position is not finite");
  const double k = options_.probe_stiffness;
  // A cut in this frame is made at its start; one between frames at the last frame's end.
  model_time_ = (frames_ - 1) * options_.frame_step;
  struct FrameEnd {
    HapticScene& s;
    ~FrameEnd() { s.model_time_ = s.frames_ * s.options_.frame_step; }
  } frame_end{*this};
  try {
    if (regions_) {
      regions_->between_frames(frames_);  // a region built beside the frames is swapped in here
      scheduled_cuts();
    }
    cut_with_blade(probe);
    if (options_.contact == ContactMode::tool && regions_) {
      const Eigen::Vector3d f = tool_frame_with_regions(probe + options_.tool_offset);
      follow_cuts();
      return f;
    }
    if (options_.contact == ContactMode::tool) {
      // The instrument itself is the tip: the tool sits there for the frame's substeps, and the
      // device receives the force the tissue exerts on it at the end of the frame.
      model_->solver().set_tool_position(0, probe + options_.tool_offset);
      model_->step(substeps_);
      follow_cuts();
      const Eigen::Vector3d f = model_->solver().tool_force(0);
      tool_touching_ = model_->solver().tool_contacts(0) > 0;
      return f;
    }
    const SurfacePoint held = contact_;
    const bool was_in_contact = in_contact_;
    update_contact(probe);
    Eigen::Vector3d f = Eigen::Vector3d::Zero();  // on the tissue
    if (in_contact_) {
      f = k * (probe - contact_.position);
      // A pushing tool cannot pull: the contact ends when the spring would draw the surface out.
      if (options_.contact == ContactMode::push && f.dot(contact_.normal) > 0) {
        in_contact_ = false;
        f.setZero();
      }
    }
    bool apply = in_contact_;
    const SurfacePoint* acted_on = &contact_;  // where the spring's force acts on the tissue
    if (options_.use_regions && in_contact_) {
      // The primary region follows the contact (built, moved or resized).
      regions_->follow(contact_.nodes, contact_.weights, frames_);
      const regions::RegionSolver* r = regions_->active();
      if (r && !(r->interior(contact_.nodes[0]) && r->interior(contact_.nodes[1]) && r->interior(contact_.nodes[2]))) {
        // Its region is being built beside the frames. The contact slides on as always (the
        // device feels the spring to it, on the published surface), and the tissue receives
        // the spring's force at the last contact point inside the current region; a new
        // contact outside it moves no tissue until its region arrives.
        if (was_in_contact && !contact_held_) held_point_ = held;
        if ((was_in_contact || contact_held_) && r->interior(held_point_.nodes[0]) &&
            r->interior(held_point_.nodes[1]) && r->interior(held_point_.nodes[2])) {
          acted_on = &held_point_;
          contact_held_ = true;
          ++live_stats_.frames_held;
        } else {
          apply = false;
          ++live_stats_.frames_unapplied;
        }
      } else {
        contact_held_ = false;
      }
    }
    if (apply)
      for (int a = 0; a < 3; ++a) applied_[a] = {acted_on->nodes[a], acted_on->weights[a] * f};
    const bool substep_spring = options_.spring_coupling == SpringCoupling::substep && apply;
    if (options_.use_regions) {
      if (substep_spring)
        regions_->frame_with_spring(contact_.nodes, contact_.weights, probe, k);
      else
        regions_->frame(apply ? applied_ : std::vector<dynamics::AppliedForce>());
    } else if (substep_spring) {
      whole_model_spring_frame(probe);
      follow_cuts();
    } else {
      model_->solver().set_applied_forces(in_contact_ ? applied_ : std::vector<dynamics::AppliedForce>());
      model_->step(substeps_);
      follow_cuts();  // a cut the config scheduled inside this frame
    }
    if (!in_contact_) return Eigen::Vector3d::Zero();
    contact_ = surface_->at(contact_.triangle, contact_.weights, contact_reading(contact_.nodes));
    const Eigen::Vector3d stretch = probe - contact_.position;
    // Divergence, caught in the frame it shows: the contact point has run off farther from the
    // tip than the organ is large (no tissue stretches that far under a probe), or is not finite.
    if (!stretch.allFinite() || stretch.norm() > runaway_distance_)
      throw NumericalError("haptic: the contact point ran away from the tip (" + std::to_string(stretch.norm()) +
                           " m, more than the organ's size): the coupling diverged");
    return -k * stretch;
  } catch (const NumericalError& e) {
    // Keep answering the device: report, return the model to rest, and start the contact anew.
    events_.push_back({frames_ - 1, e.what()});
    back_to_rest();
    return Eigen::Vector3d::Zero();
  }
}

}  // namespace softsim::haptic
