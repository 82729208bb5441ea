#include "softsim/hybrid/dhd_scene.hpp"

#include <algorithm>
#include <chrono>
#include <sstream>

#include "softsim/cutting/live_mesh.hpp"
#include "softsim/cutting/pieces.hpp"
#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/io/errors.hpp"

namespace softsim::hybrid {

dynamics::ExplicitOptions explicit_options(const DhdConfig& c, double dt) {
  dynamics::ExplicitOptions o;
  o.dt = dt;
  o.steps = c.explicit_solver.steps;
  o.damping_alpha = c.damping_alpha;
  o.threads = c.threads;
  o.energy_interval = c.explicit_solver.energy_interval;
  o.energy_growth_limit = c.explicit_solver.energy_growth_limit;
  o.contact_search = c.explicit_solver.contact_search;
  o.trajectory_nodes = c.output.trajectory_nodes;
  o.trajectory_interval = c.output.trajectory_interval;
  o.snapshot_interval = c.output.vtu_interval;
  return o;
}

DhdScene::DhdScene(std::shared_ptr<const mesh::TetMesh> mesh, DhdConfig config)
    : DhdScene(mesh, config, make_partition(*mesh, config.partition)) {}

DhdScene::DhdScene(std::shared_ptr<const mesh::TetMesh> mesh, DhdConfig config, std::vector<fem::ElementKind> kinds)
    : mesh_(std::move(mesh)), config_(std::move(config)), kinds_(std::move(kinds)) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  if (config_.separates && !config_.static_solver) {
    auto own = std::make_shared<mesh::TetMesh>(*mesh_);
    cut_mesh_ = own.get();
    mesh_ = std::move(own);
  }
  if (static_cast<int>(kinds_.size()) != mesh_->num_tets())
    throw InputError("partition: " + std::to_string(kinds_.size()) + " element kinds for " +
                     std::to_string(mesh_->num_tets()) + " tetrahedra");
  critical_ = dynamics::critical_time_step(*mesh_, config_.material.elastic);
  if (!config_.static_solver) {
    // The limit the step is chosen against: the altitude estimate, or 2/ω_max at rest.
    dynamics::CriticalStep limit = critical_;
    if (config_.explicit_solver.critical_step == CriticalStepMethod::power_iteration) {
      spectral_ = dynamics::power_iteration_step(*mesh_, kinds_, config_.material, config_.scene);
      limit.dt = spectral_->dt;
    }
    step_ = dynamics::choose_time_step(limit, config_.explicit_solver.dt, config_.explicit_solver.safety_factor,
                                       config_.explicit_solver.force_dt);
    elements_ = std::make_unique<fem::ElementSet>(
        *mesh_, kinds_, config_.material, 128,
        config_.separates ? fem::LinearForces::per_element : fem::LinearForces::assembled);
    elements_->set_linear_precision(config_.explicit_solver.linear_precision);
    // The critical step of the deformed mesh: TLED and ANP stiffness follows the deformation,
    // small-strain and corotational stiffness does not. Nor does an inversion-robust law's in the
    // sense of 000 eq. 34: its tangent on the reference gradients stays bounded as an element
    // flattens (no 1/J), while the deformed altitude goes to zero and would stop the run there.
    std::vector<char> follows(kinds_.size());
    for (std::size_t e = 0; e < kinds_.size(); ++e)
      follows[e] = (kinds_[e] == fem::ElementKind::tled || fem::volumetric_at_nodes(kinds_[e])) &&
                   !elements_->inversion_allowed(kinds_[e]);
    deformed_step_ =
        std::make_unique<dynamics::DeformedCriticalStep>(*mesh_, std::move(follows), config_.material.elastic);
    dynamics::ExplicitOptions options = explicit_options(config_, step_.dt);
    // With power iteration the deformed estimate keeps its ratio to the rest state: eq. 34 on
    // the current geometry says by how much deformation shortens the limit, 2/ω_max at rest
    // where it starts (no eigenvalue solve inside the step loop).
    spectral_scale_ = spectral_ ? spectral_->dt / critical_.dt : 1.0;
    options.critical_step = [this](const double* u) { return spectral_scale_ * deformed_step_->at(u).dt; };
    // The automatic step is re-estimated as the mesh deforms; a requested one is kept.
    options.adapt_step = !config_.explicit_solver.dt && config_.explicit_solver.dt_check_interval > 0;
    options.step_safety = config_.explicit_solver.safety_factor;
    options.step_check_interval = std::max(config_.explicit_solver.dt_check_interval, 1);
    options.elements_removed = [d = deformed_step_.get()](const std::vector<int>& e) { d->remove(e); };
    for (const auto& c : config_.cuts) options.event_times.push_back(c.time);
    options.on_event = [this](int k) { cut(config_.cuts[k].sweep, config_.cuts[k].mode); };
    solver_ = std::make_unique<dynamics::ExplicitSolver>(
        *elements_, dynamics::lumped_mass(*mesh_, config_.material.elastic.density), config_.scene, options);
  }
  setup_seconds_ = std::chrono::duration<double>(Clock::now() - t0).count();
}

dynamics::ExplicitSolver& DhdScene::solver() {
  if (!solver_) throw InputError("solver: the config's solver is static; step() needs \"kind\": \"explicit\"");
  return *solver_;
}

const dynamics::ExplicitSolver& DhdScene::solver() const { return const_cast<DhdScene*>(this)->solver(); }

int DhdScene::constraint_index(const std::string& name) const {
  const auto& cs = config_.scene.constraints;
  std::string known;
  for (std::size_t c = 0; c < cs.size(); ++c) {
    if (cs[c].name == name) return static_cast<int>(c);
    known += (known.empty() ? "\"" : ", \"") + cs[c].name + "\"";
  }
  throw InputError("boundary: no constraint named \"" + name + "\" (the scene has " +
                   (known.empty() ? std::string("none") : known) + ")");
}

void DhdScene::set_probe_position(const Eigen::Vector3d& x) {
  const auto& probe = config_.scene.probe;
  if (!config_.scene.has_probe) throw InputError("probe: the scene has no probe (boundary.probe)");
  solver().set_probe_tip(x - mesh_->nodes[probe.node]);
}

Eigen::Vector3d DhdScene::probe_position() const {
  if (!config_.scene.has_probe) throw InputError("probe: the scene has no probe (boundary.probe)");
  const auto& probe = solver().scene().probe;
  return mesh_->nodes[probe.node] + probe.tip_displacement(time());
}

dynamics::ExplicitResult DhdScene::run(const dynamics::SnapshotFn& snapshot, const dynamics::ProgressFn& progress) {
  return solver().run(snapshot, progress);
}

DhdScene::CutEvent DhdScene::cut(const cutting::BladeSweep& sweep, CutMode mode, const double* u) {
  using Clock = std::chrono::steady_clock;
  const std::string problem = cutting::sweep_problem(sweep);
  if (!problem.empty()) throw InputError("cut: expected " + problem);
  dynamics::ExplicitSolver& s = solver();
  if (held_.empty()) {
    held_.assign(mesh_->num_nodes(), 0);
    for (const auto& c : config_.scene.constraints)
      for (int node : c.nodes) held_[node] = 1;
  }
  if (!cut_grid_) cut_grid_ = std::make_unique<cutting::ElementGrid>(*mesh_);
  if (mode == CutMode::separate && !cut_mesh_)
    throw InputError("cut: separation along faces needs a scene set up for it (a \"separate\" cut in the config)");
  CutEvent ev;
  ev.time = s.time();
  ev.step = s.steps_done();
  ev.mode = mode;
  const auto t0 = Clock::now();
  const std::vector<int> crossed =
      cutting::elements_crossed(*mesh_, u ? u : s.displacement(), sweep, *cut_grid_, cut_candidates_,
                                [&](int e) { return elements_->removed(e); });
  ev.search_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  if (crossed.empty()) {  // a sweep through cut space or beside the organ: nothing changes
    ev.pieces = cut_events_.empty() ? 1 : cut_events_.back().pieces;
    ev.loose_pieces = cut_events_.empty() ? 0 : cut_events_.back().loose_pieces;
    return ev;
  }
  if (mode == CutMode::separate) {
    ev = separate(sweep, ev, crossed, u ? u : s.displacement());
    if (ev.faces == 0) return ev;
  } else {
    ev.report = s.remove_elements(*mesh_, crossed);
  }
  const auto t1 = Clock::now();
  const cutting::Pieces pieces = cutting::find_pieces(
      *mesh_, [&](int e) { return elements_->removed(e); }, [&](int node) { return held_[node] != 0; });
  ev.pieces_seconds = std::chrono::duration<double>(Clock::now() - t1).count();
  ev.pieces = pieces.count;
  ev.loose_pieces = static_cast<int>(pieces.loose.size());
  if (spectral_) recheck_spectral_step(ev);
  cut_events_.push_back(ev);
  return ev;
}

// A cut leaves every element as it was, so 000 eq. 34's element bound (the altitude estimate)
// holds as before; the lumped system's own 2/ω_max, however, may move toward that bound (a node
// that loses elements loses mass faster than stiffness). A step taken from power iteration is
// therefore measured again on the cut system (the elements left, the mesh as cut), and the run's
// step follows: an automatic step is lowered at once if it now exceeds the new limit; a requested
// one that does is a numerical failure naming the cut.
void DhdScene::recheck_spectral_step(CutEvent& ev) {
  const auto t0 = std::chrono::steady_clock::now();
  const cutting::LiveMesh live = cutting::live_mesh(*mesh_, kinds_, [&](int e) { return elements_->removed(e); });
  spectral_ = dynamics::power_iteration_step(live.mesh, live.kinds, config_.material, config_.scene);
  spectral_scale_ = spectral_->dt / critical_.dt;
  ev.stable_step = spectral_->dt;
  ev.step_check_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  dynamics::ExplicitSolver& s = solver();
  if (s.options().adapt_step) {
    s.recheck_step();
  } else if (s.dt() > spectral_->dt) {
    std::ostringstream msg;
    msg << "cut at t = " << ev.time << " s: the stable step of the cut system is " << spectral_->dt
        << " s (2/omega_max, power iteration), below the requested step " << s.dt() << " s";
    throw NumericalError(msg.str());
  }
}

double DhdScene::prepare_cuts() {
  const auto t0 = std::chrono::steady_clock::now();
  if (!cut_grid_) cut_grid_ = std::make_unique<cutting::ElementGrid>(*mesh_);
  if (cut_mesh_ && !topology_) topology_ = std::make_unique<cutting::FaceTopology>(*mesh_);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The faces between the elements on either side of the sweep open, by node copies: the plan
// (which faces, which nodes), then the mesh, then the engine, each a local update.
DhdScene::CutEvent DhdScene::separate(const cutting::BladeSweep& sweep, CutEvent ev, const std::vector<int>& crossed,
                                      const double* u) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  if (!topology_) topology_ = std::make_unique<cutting::FaceTopology>(*mesh_);
  const auto removed = [&](int e) { return elements_->removed(e); };
  const auto held = [&](int node) { return held_[node] != 0; };  // held_ covers every node (resized below)
  const cutting::SeparationPlan plan =
      cutting::plan_separation(*mesh_, u, sweep, crossed, *topology_, removed, held);
  ev.faces = static_cast<int>(plan.faces.size());
  ev.held_nodes_kept = plan.held_nodes_kept;
  if (plan.empty()) return ev;
  ev.boundary = cutting::apply_separation(*cut_mesh_, *topology_, plan);
  std::vector<fem::ElementSet::NodeCopy> copies;
  for (const auto& split : plan.splits) {
    copies.push_back({split.node, split.copy, split.elements});
    ev.copies.push_back({split.node, split.copy});
    ev.moved_elements.insert(ev.moved_elements.end(), split.elements.begin(), split.elements.end());
  }
  std::sort(ev.moved_elements.begin(), ev.moved_elements.end());
  ev.moved_elements.erase(std::unique(ev.moved_elements.begin(), ev.moved_elements.end()), ev.moved_elements.end());
  solver().split_nodes(*mesh_, copies);
  held_.resize(mesh_->num_nodes(), 0);
  ev.separation_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return ev;
}

dynamics::StaticResult DhdScene::solve_static() const {
  return dynamics::solve_static(*mesh_, kinds_, config_.material, config_.scene, config_.static_options);
}

}  // namespace softsim::hybrid
