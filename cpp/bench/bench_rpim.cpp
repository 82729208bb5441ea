// Speed of the RPIM precompute of 002 on its plate (363 nodes, 64 cells × 4³ Gauss points).
// The paper reports 647 s per full meshless solve (002 §5.1.2); the target here is the whole
// precompute — shape functions, assembly, factorisation and all 100 + 3n load cases of the
// datasets (n = 5 per axis) — in under one second. Each stage is also timed on its own.
#include <benchmark/benchmark.h>

#include "softsim/meshless/assembly.hpp"
#include "softsim/meshless/load_cases.hpp"
#include "softsim/meshless/penalty.hpp"
#include "softsim/meshless/plate_dataset.hpp"
#include "softsim/meshless/stiffness_solver.hpp"

using namespace softsim::meshless;

namespace {

struct Plate {
  PlateScene scene;
  RpimSettings settings;
  MeshlessProblem problem = plate_problem(scene);
  QuadraturePoints quadrature = box_quadrature(problem.origin, problem.size, problem.cells, problem.gauss_order);
  RbfParams rbf = resolve_rbf(settings, plate_mean_spacing(scene));
  SupportRule support = resolve_support(settings, plate_mean_spacing(scene));
};

const Plate& plate() {
  static const Plate p;
  return p;
}

// 100 random forces + n = 5 per axis + the 3 unit forces, all at node 61.
std::vector<Eigen::Vector3d> all_forces() {
  std::vector<Eigen::Vector3d> f;
  DatasetSpec spec;
  spec.kind = DatasetKind::random;
  spec.count = 100;
  f = dataset_forces(spec);
  for (const auto kind : {DatasetKind::axis_x, DatasetKind::axis_y, DatasetKind::axis_z}) {
    spec.kind = kind;
    spec.count = 5;
    for (const auto& v : dataset_forces(spec)) f.push_back(v);
  }
  return f;
}

void BM_ShapeFunctions(benchmark::State& state) {
  const Plate& p = plate();
  for (auto _ : state) {
    ShapeTable t = build_shape_table(p.problem.nodes, p.quadrature, p.support, p.rbf);
    benchmark::DoNotOptimize(t.phi.data());
  }
  state.counters["gauss_points"] = static_cast<double>(p.quadrature.points.size());
}
BENCHMARK(BM_ShapeFunctions)->Unit(benchmark::kMillisecond);

void BM_Assembly(benchmark::State& state) {
  const Plate& p = plate();
  const ShapeTable t = build_shape_table(p.problem.nodes, p.quadrature, p.support, p.rbf);
  const LameParameters m = lame_from_young(p.problem.youngs_modulus, p.problem.poisson_ratio);
  for (auto _ : state) {
    SparseMatrix k = assemble_stiffness(t, static_cast<int>(p.problem.nodes.size()), m);
    benchmark::DoNotOptimize(k.valuePtr());
  }
}
BENCHMARK(BM_Assembly)->Unit(benchmark::kMillisecond);

void BM_Factorisation(benchmark::State& state) {
  const Plate& p = plate();
  const ShapeTable t = build_shape_table(p.problem.nodes, p.quadrature, p.support, p.rbf);
  SparseMatrix k = assemble_stiffness(t, static_cast<int>(p.problem.nodes.size()),
                                      lame_from_young(p.problem.youngs_modulus, p.problem.poisson_ratio));
  apply_penalty(k, p.problem.constraints, p.settings.penalty);
  const SolverKind kind = state.range(0) == 0 ? SolverKind::sparse_ldlt : SolverKind::dense_llt;
  for (auto _ : state) {
    StiffnessSolver solver(kind);
    solver.factorize(k);
    benchmark::DoNotOptimize(&solver);
  }
  state.SetLabel(solver_name(kind));
}
BENCHMARK(BM_Factorisation)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_Solves(benchmark::State& state) {
  const Plate& p = plate();
  const RpimModel model(p.problem, p.settings);
  const auto forces = all_forces();
  const int l = plate_loaded_node_index(p.scene);
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(3 * model.num_nodes(), forces.size() + 3);
  for (std::size_t c = 0; c < forces.size(); ++c) f.block<3, 1>(3 * l, c) = forces[c];
  for (int a = 0; a < 3; ++a) f(3 * l + a, forces.size() + a) = 1.0;
  for (auto _ : state) {
    Eigen::MatrixXd u = model.solve(f);
    benchmark::DoNotOptimize(u.data());
  }
  state.counters["load_cases"] = static_cast<double>(f.cols());
}
BENCHMARK(BM_Solves)->Unit(benchmark::kMillisecond);

// Everything a user waits for: build, factor and solve all 100 + 3·5 dataset cases (+ 3 unit).
void BM_FullPrecompute(benchmark::State& state) {
  const Plate& p = plate();
  const auto forces = all_forces();
  RpimSettings settings = p.settings;
  settings.solver = state.range(0) == 0 ? SolverKind::sparse_ldlt : SolverKind::dense_llt;
  PlateRunTimings last;
  for (auto _ : state) {
    PlateRun run = run_plate(p.scene, settings, forces, false);
    benchmark::DoNotOptimize(run.displacements.data());
    last = run.timings;
  }
  state.counters["shape_functions_s"] = last.build.shape_functions_s;
  state.counters["assembly_s"] = last.build.assembly_s;
  state.counters["factorisation_s"] = last.build.factorisation_s;
  state.counters["solves_s"] = last.solves_s;
  state.counters["load_cases"] = static_cast<double>(forces.size() + 3);
  state.SetLabel(solver_name(settings.solver) + ", target < 1 s (002: 647 s per solve)");
}
BENCHMARK(BM_FullPrecompute)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
