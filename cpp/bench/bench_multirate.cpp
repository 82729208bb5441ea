// Time per haptic frame of the whole model and of the asynchronous regions (001 §5-6) on the
// 1-D bar, and of the exact reference, for a few model sizes, primary sizes and secondary
// rates. Counters: the nodes of the bar, the primary size, the secondary interval.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "softsim/multirate/async_solver.hpp"
#include "softsim/multirate/bar_model.hpp"
#include "softsim/multirate/exact_reference.hpp"
#include "softsim/multirate/whole_model.hpp"

using namespace softsim::multirate;

namespace {

ReducedSystem bar(int nodes) {
  BarSpec b;
  b.nodes = nodes;
  b.length = 0.04;
  b.area = 1e-4;
  b.youngs_modulus = 5e3;
  b.density = 1000.0;
  ReducedSystem sys = reduce(make_bar(b));
  set_mass_proportional_damping(sys, 2.0 * 0.3 * lowest_natural_frequency(sys));
  return sys;
}

// The haptic loop's work per frame without recording: spring force, one frame, new contact.
void drive(benchmark::State& state, FrameStepper& stepper) {
  Eigen::VectorXd f(1);
  long n = 0;
  for (auto _ : state) {
    const double probe = 1e-3 * std::sin(6.283185307179586 * 2.0 * 1e-3 * static_cast<double>(n++));
    f[0] = 10.0 * (probe - stepper.contact_displacement(0));
    stepper.advance(f);
    benchmark::DoNotOptimize(stepper.contact_displacement(0));
  }
  state.counters["frames_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Whole(benchmark::State& state) {
  const ReducedSystem sys = bar(static_cast<int>(state.range(0)));
  const auto ls = state.range(1) ? LinearSolverKind::kDense : LinearSolverKind::kSparse;
  WholeModel whole(sys, sys.num_free_nodes() - 1, SolverSpec{}, 1e-3, ls);
  drive(state, whole);
  state.counters["nodes"] = static_cast<double>(state.range(0));
}

void BM_Async(benchmark::State& state) {
  const ReducedSystem sys = bar(static_cast<int>(state.range(0)));
  AsyncSpec spec;
  spec.primary.min_nodes = spec.primary.max_nodes = static_cast<int>(state.range(1));
  spec.secondary = {{0, static_cast<int>(state.range(2)), SolverSpec{}}};
  spec.linear_solver = state.range(3) ? LinearSolverKind::kDense : LinearSolverKind::kSparse;
  AsyncSolver async(sys, sys.num_free_nodes() - 1, spec);
  drive(state, async);
  state.counters["nodes"] = static_cast<double>(state.range(0));
  state.counters["primary"] = static_cast<double>(state.range(1));
  state.counters["every"] = static_cast<double>(state.range(2));
}

void BM_Exact(benchmark::State& state) {
  const ReducedSystem sys = bar(static_cast<int>(state.range(0)));
  ExactReference exact(sys, sys.num_free_nodes() - 1, 1e-3);
  drive(state, exact);
  state.counters["nodes"] = static_cast<double>(state.range(0));
}

}  // namespace

// {nodes, dense?}
BENCHMARK(BM_Whole)->Args({40, 0})->Args({40, 1})->Args({400, 0})->Args({400, 1});
// {nodes, primary, every, dense?}
BENCHMARK(BM_Async)
    ->Args({40, 5, 20, 0})->Args({40, 10, 20, 0})->Args({40, 30, 20, 0})->Args({40, 5, 2, 0})
    ->Args({40, 5, 20, 1})->Args({40, 30, 20, 1})
    ->Args({400, 20, 20, 0})->Args({400, 50, 20, 0})->Args({400, 20, 20, 1})->Args({400, 50, 20, 1});
BENCHMARK(BM_Exact)->Arg(40);
