#include "softsim/hybrid/dhd_run.hpp"

#include <algorithm>
#include <chrono>
#include <type_traits>

#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/dynamics/node_selection.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/hybrid/dhd_scene.hpp"
#include "softsim/hybrid/law_parameters.hpp"

namespace softsim::hybrid {

namespace {

nlohmann::json vec3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json field(const std::vector<double>& u) {
  nlohmann::json a = nlohmann::json::array();
  for (std::size_t i = 0; i + 2 < u.size(); i += 3) a.push_back({u[i], u[i + 1], u[i + 2]});
  return a;
}

}  // namespace

nlohmann::json element_kind_legend() {
  nlohmann::json legend = nlohmann::json::array();
  for (const fem::ElementKindInfo& info : fem::kElementKinds)
    legend.push_back({{"name", info.name}, {"small_strain", info.small_strain}, {"description", info.description}});
  return legend;
}

DhdRun run_dhd(const mesh::TetMesh& mesh, const DhdConfig& c, const dynamics::SnapshotFn& snapshot) {
  return run_dhd(mesh, c, make_partition(mesh, c.partition), snapshot, {});
}

DhdRun run_dhd(const mesh::TetMesh& mesh, const DhdConfig& c, std::vector<fem::ElementKind> kinds,
               const dynamics::SnapshotFn& snapshot, const dynamics::ProgressFn& progress,
               const std::function<void(const DhdScene&)>& on_scene) {
  // The scene borrows the caller's mesh for the run (no copy).
  DhdScene scene(std::shared_ptr<const mesh::TetMesh>(&mesh, [](const mesh::TetMesh*) {}), c, std::move(kinds));
  if (on_scene) on_scene(scene);
  DhdRun run;
  run.critical = scene.critical_step();
  run.spectral = scene.spectral_step();
  run.setup_seconds = scene.setup_seconds();
  if (scene.is_static()) {
    // Wall time of the Newton solve alone (assembly, factorisations, increments), the static
    // counterpart of the explicit stepping loop's wall_seconds.
    const auto t0 = std::chrono::steady_clock::now();
    run.static_result = scene.solve_static();
    run.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    SmallStrainCheck check(mesh, scene.kinds());
    check.observe(run.static_result->displacement.data(), 0.0);
    run.small_strain = check.record();
  } else {
    run.step = scene.step_choice();
    SmallStrainCheck check(scene.mesh(), scene.kinds());  // the scene's: separating cuts re-point elements
    const auto removed = [&](int e) { return scene.removed(e); };
    run.explicit_result = scene.run(snapshot, [&](int steps_done, double time) {
      check.observe(scene.displacement(), time, removed);
      if (progress) progress(steps_done, time);
    });
    check.observe(run.explicit_result->displacement.data(), run.explicit_result->time, removed);
    run.small_strain = check.record();
    run.cuts = scene.cut_events();
    for (const auto& ev : run.cuts)
      run.removed_elements.insert(run.removed_elements.end(), ev.report.elements.begin(), ev.report.elements.end());
    std::sort(run.removed_elements.begin(), run.removed_elements.end());
    if (c.separates) run.cut_mesh = scene.mesh_ptr();
  }
  run.kinds = scene.kinds();
  return run;
}

nlohmann::json result_payload(const mesh::TetMesh& mesh, const DhdConfig& c, const DhdRun& run) {
  nlohmann::json p;
  // The full field is most of the artifact on a large mesh; a run read only for its trajectories,
  // reactions or timing leaves it out (output.displacement = false).
  if (c.output.displacement)
    p["displacement"] = field(run.explicit_result ? run.explicit_result->displacement : run.static_result->displacement);
  if (c.output.velocity && run.explicit_result) p["velocity"] = field(run.explicit_result->velocity);
  std::vector<int> kinds(run.kinds.size());
  std::array<int, fem::kNumElementKinds> counts{};
  for (std::size_t e = 0; e < kinds.size(); ++e) {
    kinds[e] = static_cast<int>(run.kinds[e]);
    ++counts[kinds[e]];
  }
  p["element_kind"] = kinds;
  p["element_kind_legend"] = element_kind_legend();
  // Every kind's count, and the realised share of the small-strain (cheap) kinds.
  nlohmann::json element_counts = nlohmann::json::object();
  int small_strain = 0;
  for (const fem::ElementKindInfo& info : fem::kElementKinds) {
    const int n = counts[static_cast<int>(info.kind)];
    element_counts[info.name] = n;
    if (info.small_strain) small_strain += n;
  }
  element_counts["linear_fraction"] = static_cast<double>(small_strain) / kinds.size();
  p["element_counts"] = element_counts;
  const auto& m = c.material;
  p["material"] = {{"model", c.model},
                   {"model_defaulted", c.model_defaulted},
                   {"E", m.elastic.youngs_modulus},
                   {"nu", m.elastic.poisson_ratio},
                   {"density", m.elastic.density},
                   {"mu", m.lame.mu},
                   {"lambda", m.lame.lambda},
                   {"bulk_modulus", bulk_modulus(m)},
                   {"wave_speed", run.critical.wave_speed}};
  add_law_parameters(m, p["material"]);
  p["mesh"] = {{"nodes", mesh.num_nodes()}, {"tets", mesh.num_tets()}};
  nlohmann::json reactions = nlohmann::json::array();
  const auto& rs = run.explicit_result ? run.explicit_result->reactions : run.static_result->reactions;
  for (std::size_t i = 0; i < rs.size(); ++i)
    reactions.push_back({{"name", c.scene.constraints[i].name}, {"force", vec3(rs[i])}});
  p["reactions"] = reactions;
  // 000 §2.2.2: small-strain elements are valid below 10 % deformation.
  const SmallStrainRecord& ss = run.small_strain;
  p["small_strain_check"] = {{"limit", kSmallStrainLimit},
                             {"elements", ss.elements},
                             {"samples", ss.samples},
                             {"largest", ss.largest},
                             {"element", ss.element},
                             {"kind", ss.element >= 0 ? fem::kind_name(run.kinds[ss.element]) : ""},
                             {"time", ss.time},
                             {"broken", ss.broken()}};

  if (run.static_result) {
    const auto& s = *run.static_result;
    p["solver"] = {{"kind", "static"},
                   // A linear model is solved once (K u = R), without increments or inversion check.
                   {"method", s.linear_solve ? "linear" : "newton"},
                   {"increments", s.linear_solve ? 1 : c.static_options.increments},
                   {"iterations", s.iterations},
                   {"residual", s.residual},
                   {"force_scale", s.force_scale},
                   {"tolerance", c.static_options.tolerance}};
    p["energies"] = {{"strain", s.strain_energy}};
    if (c.scene.has_probe)
      p["probe"] = {{"node", c.scene.probe.node}, {"final_force", vec3(s.probe_force)}};
    p["timing"] = {{"setup_seconds", run.setup_seconds}, {"solve_seconds", run.solve_seconds}};
    return p;
  }
  const auto& r = *run.explicit_result;
  // The step sizes used: [first step, time (s), dt (s)] per size, one entry at a constant step.
  nlohmann::json dt_history = nlohmann::json::array();
  for (const auto& seg : r.step_history) dt_history.push_back({seg.first_step, seg.time, seg.dt});
  const int step_checks = c.explicit_solver.dt ? 0 : c.explicit_solver.dt_check_interval;
  const double chosen_critical = run.spectral ? run.spectral->dt : run.critical.dt;
  p["solver"] = {{"kind", "explicit"},
                 {"method", "central_difference"},
                 {"steps", r.steps},
                 {"dt", r.dt},
                 {"dt_critical", run.critical.dt},
                 {"min_altitude", run.critical.min_altitude},
                 {"wave_speed", run.critical.wave_speed},
                 {"critical_step", critical_step_name(c.explicit_solver.critical_step)},
                 {"safety_factor", c.explicit_solver.dt ? r.dt / chosen_critical : c.explicit_solver.safety_factor},
                 {"dt_forced", run.step.forced},
                 {"dt_check_interval", step_checks},
                 {"dt_final", r.step_history.empty() ? r.dt : r.step_history.back().dt},
                 {"dt_history", dt_history},
                 {"time", r.time},
                 {"damping_alpha", c.damping_alpha}};
  if (run.spectral)  // beside the altitude estimate: 2/ω_max of the lumped system at rest
    p["solver"]["dt_critical_power_iteration"] = {{"dt", run.spectral->dt},
                                                  {"omega_max", run.spectral->omega_max},
                                                  {"rayleigh_quotient", run.spectral->rayleigh},
                                                  {"residual", run.spectral->residual},
                                                  {"tolerance", run.spectral->tolerance},
                                                  {"iterations", run.spectral->iterations},
                                                  {"converged", run.spectral->converged}};
  nlohmann::json en = {{"time", nlohmann::json::array()},
                       {"kinetic", nlohmann::json::array()},
                       {"strain", nlohmann::json::array()},
                       {"external_work", nlohmann::json::array()},
                       {"dissipated", nlohmann::json::array()}};
  for (const auto& s : r.energies) {
    en["time"].push_back(s.time);
    en["kinetic"].push_back(s.kinetic);
    en["strain"].push_back(s.strain);
    en["external_work"].push_back(s.external_work);
    en["dissipated"].push_back(s.dissipated);
    if (!c.cuts.empty()) en["removed"].push_back(s.removed);
  }
  p["energies"] = en;
  if (!c.scene.tools.empty()) {
    // The force on each rigid tool at the energy samples' times (what a haptic device renders).
    nlohmann::json tools = nlohmann::json::array();
    static constexpr const char* kShape[] = {"sphere", "capsule", "plane", "mesh"};
    for (std::size_t k = 0; k < c.scene.tools.size(); ++k) {
      nlohmann::json force = nlohmann::json::array();
      for (const auto& f : r.tool_force[k]) force.push_back(vec3(f));
      tools.push_back({{"name", c.scene.tools[k].name},
                       {"shape", kShape[static_cast<int>(c.scene.tools[k].shape)]},
                       {"nodes", c.scene.tools[k].nodes.size()},
                       {"time", en["time"]},
                       {"force", force},
                       {"contacts", r.tool_contacts[k]}});
      if (const auto& s = c.scene.tools[k].surface)
        tools.back()["surface"] = {{"triangles", s->num_triangles()}, {"volume", s->volume()}};
    }
    p["tools"] = tools;
  }
  if (!c.cuts.empty()) {
    nlohmann::json cuts = nlohmann::json::array();
    for (const auto& ev : run.cuts)
      cuts.push_back({{"time", ev.time},
                      {"step", ev.step},
                      {"elements_removed", ev.report.elements.size()},
                      {"mass_removed", ev.report.mass},
                      {"strain_energy_removed", ev.report.strain_energy},
                      {"kinetic_energy_removed", ev.report.kinetic_energy},
                      {"detached_nodes", ev.report.detached_nodes},
                      {"pieces", ev.pieces},
                      {"loose_pieces", ev.loose_pieces},
                      {"search_seconds", ev.search_seconds},
                      {"update_seconds", ev.report.seconds},
                      {"pieces_seconds", ev.pieces_seconds},
                      {"mode", ev.mode == CutMode::separate ? "separate" : "remove"},
                      {"faces_opened", ev.faces},
                      {"node_copies", ev.copies.size()},
                      {"held_nodes_kept", ev.held_nodes_kept},
                      {"separation_seconds", ev.separation_seconds},
                      {"stable_step", ev.stable_step},
                      {"step_check_seconds", ev.step_check_seconds}});
    p["cuts"] = cuts;
    p["removed_elements"] = run.removed_elements;
    if (c.separates) {
      // Node copies in the order they were made: copy k is node num_nodes + k of the mesh given.
      nlohmann::json copies = nlohmann::json::array();
      for (const auto& ev : run.cuts)
        for (const auto& [node, copy] : ev.copies) copies.push_back({node, copy});
      p["node_copies"] = copies;
      // The elements whose corners moved to copies, with their corners now ([e, a, b, c, d]), so
      // that the cut mesh can be drawn from the mesh given.
      nlohmann::json moved = nlohmann::json::array();
      if (run.cut_mesh)
        for (int e = 0; e < mesh.num_tets(); ++e)
          if (run.cut_mesh->tets[e] != mesh.tets[e]) {
            const auto& t = run.cut_mesh->tets[e];
            moved.push_back({e, t[0], t[1], t[2], t[3]});
          }
      p["moved_elements"] = moved;
    }
  }
  if (!c.output.trajectory_nodes.empty()) {
    nlohmann::json disp = nlohmann::json::array();
    for (const auto& tr : r.trajectories) {
      nlohmann::json one = nlohmann::json::array();
      for (const auto& v : tr) one.push_back(vec3(v));
      disp.push_back(one);
    }
    p["trajectories"] = {{"nodes", c.output.trajectory_nodes}, {"time", r.trajectory_time}, {"displacement", disp}};
  }
  if (c.scene.has_probe) {
    nlohmann::json f = nlohmann::json::array();
    for (const auto& v : r.probe_force) f.push_back(vec3(v));
    p["probe"] = {{"node", c.scene.probe.node},
                  {"time", r.probe_time},
                  {"force", f},
                  {"final_force", r.probe_force.empty() ? vec3(Eigen::Vector3d::Zero()) : vec3(r.probe_force.back())}};
  }
  nlohmann::json ns = nlohmann::json::object();
  for (int k = 0; k < fem::kNumElementKinds; ++k)
    if (r.timing.element_counts[k] > 0 && r.steps > 0)
      ns[fem::kind_name(static_cast<fem::ElementKind>(k))] = r.timing.ns_per_element(k, r.steps);
  p["timing"] = {{"threads", r.timing.threads},
                 {"steps", r.steps},
                 {"wall_seconds", r.timing.wall_seconds},
                 {"steps_per_second", r.timing.steps_per_second},
                 {"setup_seconds", run.setup_seconds},
                 {"sample_seconds", r.timing.sample_seconds},
                 {"ns_per_element", ns},
                 {"node_phase_ns_per_node", r.timing.ns_per_node(mesh.num_nodes(), r.steps)},
                 {"contact_seconds", r.timing.contact_seconds}};
  return p;
}

dynamics::Scene default_bench_scene(const mesh::TetMesh& mesh, double ramp_time) {
  dynamics::Scene scene;
  const auto [lo, hi] = mesh::bounding_box(mesh);
  const auto bottom = mesh.node_sets.find("bottom");
  if (bottom != mesh.node_sets.end() && !bottom->second.empty()) {
    dynamics::DisplacementConstraint fixed;
    fixed.name = "fixed bottom";
    fixed.nodes = bottom->second;
    scene.constraints.push_back(fixed);
  }
  dynamics::DisplacementConstraint push;
  push.name = "prescribed top centre";
  push.nodes = {dynamics::nearest_node(mesh, default_operating_point(mesh))};
  push.displacement = Eigen::Vector3d(0, 0, -0.1 * (hi.z() - lo.z()));
  push.ramp.duration = ramp_time;
  scene.constraints.push_back(push);
  return scene;
}

std::vector<BenchRun> run_bench(const mesh::TetMesh& mesh, const DhdConfig& c) {
  const dynamics::CriticalStep critical = dynamics::critical_time_step(mesh, c.material.elastic);
  const double dt = dynamics::choose_time_step(critical, c.explicit_solver.dt, c.explicit_solver.safety_factor,
                                               c.explicit_solver.force_dt)
                        .dt;
  const dynamics::Scene scene = c.has_boundary ? c.scene : default_bench_scene(mesh, c.bench.steps * dt);
  const std::vector<double> masses = dynamics::lumped_mass(mesh, c.material.elastic.density);

  struct Variant {
    std::string name;
    PartitionSpec spec;
  };
  std::vector<Variant> variants;
  if (!c.linear_material) {
    PartitionSpec all_tled;
    all_tled.uniform_element = fem::ElementKind::tled;
    variants.push_back({"all_tled", all_tled});
  }
  PartitionSpec all_linear;
  all_linear.uniform_element = fem::ElementKind::linear;
  variants.push_back({"all_linear", all_linear});
  PartitionSpec all_corot;
  all_corot.uniform_element = fem::ElementKind::corotational;
  variants.push_back({"all_corotational", all_corot});
  if (!c.linear_material)
    for (double r : c.bench.linear_fractions) {
      PartitionSpec mixed;
      mixed.kind = PartitionKind::linear_fraction;
      mixed.linear_fraction = r;
      variants.push_back({"linear_fraction", mixed});
    }

  std::vector<BenchRun> out;
  for (const Variant& v : variants) {
    // One element set per partition: every run recomputes its state from u0.
    fem::ElementSet elements(mesh, make_partition(mesh, v.spec), c.material);
    elements.set_linear_precision(c.explicit_solver.linear_precision);
    for (int threads : c.bench.threads) {
      dynamics::ExplicitOptions o;
      o.dt = dt;
      o.steps = c.bench.steps;
      o.damping_alpha = c.damping_alpha;
      o.threads = threads;
      o.energy_interval = c.bench.steps;  // timing of the stepping loop, one energy check
      o.energy_growth_limit = c.explicit_solver.energy_growth_limit;
      dynamics::ExplicitSolver solver(elements, masses, scene, o);
      const dynamics::ExplicitResult r = solver.run();
      BenchRun b;
      b.partition = v.name;
      b.linear_fraction = v.spec.kind == PartitionKind::linear_fraction ? v.spec.linear_fraction
                          : v.spec.uniform_element == fem::ElementKind::tled ? 0.0
                                                                               : 1.0;
      b.threads = threads;
      b.steps = r.steps;
      b.steps_per_second = r.timing.steps_per_second;
      for (int k = 0; k < fem::kNumElementKinds; ++k) b.ns_per_element[k] = r.timing.ns_per_element(k, r.steps);
      b.node_ns_per_node = r.timing.ns_per_node(mesh.num_nodes(), r.steps);
      out.push_back(b);
    }
  }
  return out;
}

nlohmann::json bench_payload(const mesh::TetMesh& mesh, const DhdConfig& c, const std::vector<BenchRun>& runs) {
  nlohmann::json rs = nlohmann::json::array();
  for (const auto& b : runs) {
    nlohmann::json ns = nlohmann::json::object();
    for (int k = 0; k < fem::kNumElementKinds; ++k)
      if (b.ns_per_element[k] > 0) ns[fem::kind_name(static_cast<fem::ElementKind>(k))] = b.ns_per_element[k];
    rs.push_back({{"partition", b.partition},
                  {"linear_fraction", b.linear_fraction},
                  {"threads", b.threads},
                  {"steps", b.steps},
                  {"steps_per_second", b.steps_per_second},
                  {"ns_per_element", ns},
                  {"node_phase_ns_per_node", b.node_ns_per_node}});
  }
  return {{"mesh", {{"nodes", mesh.num_nodes()}, {"tets", mesh.num_tets()}}},
          {"material", {{"model", c.model}, {"model_defaulted", c.model_defaulted}, {"E", c.material.elastic.youngs_modulus},
                        {"nu", c.material.elastic.poisson_ratio}, {"density", c.material.elastic.density}}},
          {"scene", c.has_boundary ? "configured" : "default: bottom fixed, top centre pushed down 10 % of the height"},
          {"precision", "double"},
          {"runs", rs}};
}

}  // namespace softsim::hybrid
