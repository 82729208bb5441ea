#include "softsim/meshless/scene_run.hpp"

#include <chrono>

namespace softsim::meshless {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

std::vector<SceneRun> run_scene_sets(const MeshlessProblem& problem, const SceneLayout& layout,
                                     const RpimSettings& settings,
                                     const std::vector<std::vector<Eigen::Vector3d>>& force_sets,
                                     bool stiffness_conditioning) {
  SceneRun shared;
  shared.loaded_node_number = layout.loaded_node_number;
  shared.loaded_node_index = layout.loaded_node_index;
  shared.top_nodes = layout.reported_nodes;
  shared.fixed_nodes = layout.fixed_nodes;

  const auto t_start = std::chrono::steady_clock::now();
  const RpimModel model(problem, settings);
  shared.nodes = model.problem().nodes;
  shared.mean_spacing = model.mean_spacing();
  shared.rbf = model.rbf();
  shared.support = model.support();
  shared.timings.build = model.timings();

  const int n = 3 * model.num_nodes();
  Eigen::VectorXd body = Eigen::VectorXd::Zero(n);
  if (layout.body_force.squaredNorm() > 0) {
    const Eigen::Vector3d b = layout.body_force;
    body = model.body_force([b](const Eigen::Vector3d&) { return b; });
  }
  const double build_s = seconds_since(t_start);
  // Each set is solved on its own, as a run of that set alone would solve it (its cases, then
  // the three unit forces): the factorisation is shared, the bits of every set unchanged.
  std::vector<SceneRun> runs;
  for (const auto& forces : force_sets) {
    SceneRun run = shared;
    run.forces = forces;
    // Point forces act on the loaded node's own dofs: RPIM shape functions interpolate, so the
    // consistent load of a force at a node is the force itself (002 eq. 25 with φ_I(x_J) = δ_IJ).
    const auto t0 = std::chrono::steady_clock::now();
    const int cases = static_cast<int>(forces.size());
    Eigen::MatrixXd f = Eigen::MatrixXd::Zero(n, cases + 3);
    for (int c = 0; c < cases; ++c) {
      f.col(c) = body;
      f.block<3, 1>(3 * run.loaded_node_index, c) += forces[c];
    }
    for (int a = 0; a < 3; ++a) f(3 * run.loaded_node_index + a, cases + a) = 1.0;
    const Eigen::MatrixXd u = model.solve(f);
    run.displacements = u.leftCols(cases);
    run.unit_solutions = u.rightCols(3);
    run.timings.solves_s = seconds_since(t0);
    run.timings.total_s = build_s + run.timings.solves_s;
    runs.push_back(std::move(run));
  }

  const auto t0 = std::chrono::steady_clock::now();
  SceneConditioning c;
  c.moment = shape_table_stats(model.shapes(), shared.nodes, shared.mean_spacing);
  c.pivot_ratio = model.solver().pivot_ratio();
  c.rigid_modes = rigid_mode_energy(model.stiffness(), shared.nodes);
  if (stiffness_conditioning) {
    c.stiffness_estimated = true;
    c.penalized = estimate_spectrum(model.penalized_stiffness(), model.solver());
    const SparseMatrix k_free = free_block(model.stiffness(), shared.fixed_nodes);
    StiffnessSolver free_solver(settings.solver);
    free_solver.factorize(k_free);
    c.free_dofs = estimate_spectrum(k_free, free_solver);
  }
  const double conditioning_s = seconds_since(t0);
  for (auto& run : runs) {
    run.conditioning = c;
    run.timings.conditioning_s = conditioning_s;
  }
  return runs;
}

}  // namespace softsim::meshless
