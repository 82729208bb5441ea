// Time per evaluation of all 121 top nodes of the 002 plate: fitted playback (the real-time
// path, target <= 10 µs), the exact superposition of unit solutions, and the relation-by-relation
// direct evaluation; plus the offline cost of a fit with cross-validated orders.
// The model is fitted to a synthetic linear plate (smooth, non-polynomial unit fields) so that the
// benchmark needs no artifact; playback cost depends only on the node count and the order of
// relation 3, not on the data.
#include <benchmark/benchmark.h>

#include <cmath>

#include "softsim/fit/fit_driver.hpp"
#include "softsim/fit/playback.hpp"
#include "softsim/fit/superposition.hpp"

using namespace softsim::fit;

namespace {

constexpr int kSide = 11;

Eigen::MatrixXd plate_nodes() {
  Eigen::MatrixXd nodes(kSide * kSide, 3);
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) nodes.row(i + kSide * j) << i * 0.0048, j * 0.0048, 0.006;
  return nodes;
}

double unit_field(int d, int c, double x, double y) {
  const double s = x / 0.048, t = y / 0.048;
  const double bump = std::sin(M_PI * s) * std::sin(M_PI * t);
  const double gain[3][3] = {{-2.8e-3, -3e-4, 6e-4}, {-3e-4, -2.8e-3, 6e-4}, {5e-4, 5e-4, -14.5e-3}};
  const double shape = c == d ? 1.0 : (c == 0 ? s - 0.5 : t - 0.5);
  return gain[d][c] * bump * shape;
}

Eigen::MatrixXd unit_solutions(const Eigen::MatrixXd& nodes) {
  Eigen::MatrixXd u(3 * nodes.rows(), 3);
  for (Eigen::Index j = 0; j < nodes.rows(); ++j)
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) u(3 * j + c, d) = unit_field(d, c, nodes(j, 0), nodes(j, 1));
  return u;
}

std::array<Dataset, 3> axis_datasets(int cases) {
  std::array<Dataset, 3> out;
  const Eigen::MatrixXd nodes = plate_nodes();
  const Eigen::MatrixXd units = unit_solutions(nodes);
  for (int d = 0; d < 3; ++d) {
    Dataset& ds = out[d];
    ds.nodes = nodes;
    ds.loaded_node = 60;
    ds.unit_solutions = units;
    for (int i = 1; i <= cases; ++i) {
      LoadCase lc;
      lc.force[d] = static_cast<double>(i) / cases;
      lc.displacement.resize(nodes.rows(), 3);
      for (Eigen::Index j = 0; j < nodes.rows(); ++j)
        for (int c = 0; c < 3; ++c) lc.displacement(j, c) = lc.force[d] * units(3 * j + c, d);
      ds.cases.push_back(lc);
    }
  }
  return out;
}

// The paper's orders (Tables 1–2): separable surfaces up to order 5, relation 3 of order k.
FitModel paper_like_model(int parameter_order) {
  static const std::array<Dataset, 3> data = axis_datasets(10);
  FitSettings s;
  for (int d = 0; d < 3; ++d) {
    s.fixed[d].force_order = 1;
    for (int c = 0; c < 3; ++c) {
      s.fixed[d].components[c].surface = SurfaceTerms::separable(c == d ? 4 : 5, c == d ? 4 : 1);
      s.fixed[d].components[c].parameter_order = parameter_order;
    }
  }
  return fit_surface_model({&data[0], &data[1], &data[2]}, s, false).model;
}

std::vector<Eigen::Vector3d> force_cycle() {
  std::vector<Eigen::Vector3d> f;
  for (int k = 0; k < 64; ++k) f.emplace_back(std::sin(0.7 * k), std::cos(1.3 * k), -std::abs(std::sin(0.37 * k)));
  return f;
}

void BM_Playback(benchmark::State& state) {
  const SurfacePlayer player(paper_like_model(static_cast<int>(state.range(0))));
  const auto forces = force_cycle();
  Eigen::VectorXd u(3 * player.node_count());
  std::size_t k = 0;
  for (auto _ : state) {
    player.play(forces[k++ % forces.size()], u.data());
    benchmark::DoNotOptimize(u.data());
    benchmark::ClobberMemory();
  }
  state.counters["nodes"] = player.node_count();
  state.counters["relation3_order"] = static_cast<double>(state.range(0));
}
BENCHMARK(BM_Playback)->Arg(1)->Arg(3)->Unit(benchmark::kNanosecond);

void BM_Superposition(benchmark::State& state) {
  const Superposition exact(unit_solutions(plate_nodes()));
  const auto forces = force_cycle();
  Eigen::VectorXd u(3 * exact.node_count());
  std::size_t k = 0;
  for (auto _ : state) {
    exact.apply(forces[k++ % forces.size()], u.data());
    benchmark::DoNotOptimize(u.data());
    benchmark::ClobberMemory();
  }
  state.counters["nodes"] = exact.node_count();
}
BENCHMARK(BM_Superposition)->Unit(benchmark::kNanosecond);

void BM_DirectEvaluation(benchmark::State& state) {
  const FitModel model = paper_like_model(1);
  const auto forces = force_cycle();
  std::size_t k = 0;
  for (auto _ : state) {
    Eigen::MatrixXd u = evaluate_direct(model, forces[k++ % forces.size()]);
    benchmark::DoNotOptimize(u.data());
  }
}
BENCHMARK(BM_DirectEvaluation)->Unit(benchmark::kMicrosecond);

// Offline: the whole fit of three directions with cross-validated orders (default limits).
void BM_FitWithCrossValidation(benchmark::State& state) {
  const std::array<Dataset, 3> data = axis_datasets(10);
  for (auto _ : state) {
    FitResult r = fit_surface_model({&data[0], &data[1], &data[2]}, FitSettings{}, false);
    benchmark::DoNotOptimize(r.model.nodes.data());
  }
}
BENCHMARK(BM_FitWithCrossValidation)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
