#include "softsim/meshless/plate_dataset.hpp"

#include <chrono>

namespace softsim::meshless {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

MeshlessProblem plate_problem(const PlateScene& scene) {
  MeshlessProblem p;
  p.nodes = plate_nodes(scene);
  p.origin = Eigen::Vector3d::Zero();
  p.size = scene.size;
  p.cells = scene.background_cells;
  p.gauss_order = scene.gauss_order;
  p.youngs_modulus = scene.youngs_modulus;
  p.poisson_ratio = scene.poisson_ratio;
  p.constraints = plate_constraints(scene);
  p.mean_spacing = plate_mean_spacing(scene);
  return p;
}

PlateRun run_plate(const PlateScene& scene, const RpimSettings& settings, const std::vector<Eigen::Vector3d>& forces,
                   bool stiffness_conditioning) {
  PlateRun run;
  run.loaded_node_number = plate_loaded_node_number(scene);
  run.loaded_node_index = plate_loaded_node_index(scene);
  run.top_nodes = plate_top_nodes(scene);
  run.fixed_nodes = plate_fixed_nodes(scene);
  run.forces = forces;

  const auto t_start = std::chrono::steady_clock::now();
  const RpimModel model(plate_problem(scene), settings);
  run.nodes = model.problem().nodes;
  run.mean_spacing = model.mean_spacing();
  run.rbf = model.rbf();
  run.support = model.support();
  run.timings.build = model.timings();

  // Point forces act on the loaded node's own dofs: RPIM shape functions interpolate, so the
  // consistent load of a force at a node is the force itself (002 eq. 25 with φ_I(x_J) = δ_IJ).
  auto t0 = std::chrono::steady_clock::now();
  const int n = 3 * model.num_nodes();
  const int cases = static_cast<int>(forces.size());
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(n, cases + 3);
  Eigen::VectorXd body = Eigen::VectorXd::Zero(n);
  if (scene.body_force.squaredNorm() > 0) {
    const Eigen::Vector3d b = scene.body_force;
    body = model.body_force([b](const Eigen::Vector3d&) { return b; });
  }
  for (int c = 0; c < cases; ++c) {
    f.col(c) = body;
    f.block<3, 1>(3 * run.loaded_node_index, c) += forces[c];
  }
  for (int a = 0; a < 3; ++a) f(3 * run.loaded_node_index + a, cases + a) = 1.0;
  const Eigen::MatrixXd u = model.solve(f);
  run.displacements = u.leftCols(cases);
  run.unit_solutions = u.rightCols(3);
  run.timings.solves_s = seconds_since(t0);
  run.timings.total_s = seconds_since(t_start);

  t0 = std::chrono::steady_clock::now();
  auto& c = run.conditioning;
  c.moment = shape_table_stats(model.shapes(), run.nodes, run.mean_spacing);
  c.pivot_ratio = model.solver().pivot_ratio();
  c.rigid_modes = rigid_mode_energy(model.stiffness(), run.nodes);
  if (stiffness_conditioning) {
    c.stiffness_estimated = true;
    c.penalized = estimate_spectrum(model.penalized_stiffness(), model.solver());
    const SparseMatrix k_free = free_block(model.stiffness(), run.fixed_nodes);
    StiffnessSolver free_solver(settings.solver);
    free_solver.factorize(k_free);
    c.free_dofs = estimate_spectrum(k_free, free_solver);
  }
  run.timings.conditioning_s = seconds_since(t0);
  return run;
}

}  // namespace softsim::meshless
