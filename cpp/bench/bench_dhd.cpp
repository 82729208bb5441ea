// Speed of the DHD-FEA explicit engine on the paper's mesh (000 §3.2, Table 1: 3564 nodes,
// 14450 tetrahedra = mesh::make_cuboid with cells {17, 17, 10}), double precision:
//   BM_Steps      explicit steps per second for all-TLED (both neo-Hookean forms), all-linear,
//                 all-corotational and a linear share r, on 1 and 2 threads;
//   BM_Kernel     the element phase alone: elements per second of each kind (1e9 / rate = ns per
//                 element; for ANP including its nodal-pressure pre-pass, for assembled linear
//                 elements the rows of every node);
//   BM_NodalForces  the element phase and the nodal sums: the complete internal forces, per
//                 element of each kind (what a linear element costs against a TLED one); both
//                 also for the r = 0.5 split (partition 15), which the two uniform ones bracket;
//   BM_LinearRows the assembled linear rows alone, streamed and cache-resident, with the engine's
//                 kernel and the portable one;
//   BM_LinearRowsMemoryFloor  reading the rows' stored values once, with no arithmetic;
//   BM_LinearRowsSingleValues the rows' product with the stored values rounded to single
//                 precision (the engine's solver.linear_precision "single");
//   BM_LinearRowsInLanes  the rows vectorised the other way (eight rows in the lanes, hardware
//                 gathers of the displacements), against the engine's kernel;
//   BM_MemoryFloorKernel  the same loads and stores as a kernel with almost no arithmetic;
//   BM_HybridSpeedUp  explicit steps, one thread, at linear shares r = 0, 0.25, 0.5, 0.75, 1 with
//                 the linear rows in double and in single precision (solver.linear_precision):
//                 000 Table 1's speed-up against all TLED.
// Scene: bottom fixed, the top-centre node pushed down (the paper's error scene, Fig. 10).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "bench/paper_mesh.hpp"
#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/dynamics/stable_step.hpp"
#include "softsim/fem/element_response.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/fem/linear_rows.hpp"
#include "softsim/fem/linear_rows_avx512.hpp"
#include "softsim/hybrid/dhd_run.hpp"
#include "softsim/hybrid/partition.hpp"
#include "softsim/mesh/cuboid.hpp"

using namespace softsim;
using fem::ElementKind;

namespace {

constexpr int kStepsPerIteration = 200;

using bench::kPaper;
using bench::paper_mesh;

// Partition codes: 0 all TLED (paper form), 1 all TLED (decoupled form), 2 all linear
// (assembled rows), 3 all corotational, 4 all ANP (decoupled form), 5 all linear element by
// element, 10..19 linear share r = (code − 10) / 10 with TLED elsewhere.
std::vector<ElementKind> partition(int code) {
  const auto& m = paper_mesh();
  hybrid::PartitionSpec spec;
  if (code <= 1) spec.uniform_element = ElementKind::tled;
  if (code == 2 || code == 5) spec.uniform_element = ElementKind::linear;
  if (code == 3) spec.uniform_element = ElementKind::corotational;
  if (code == 4) spec.uniform_element = ElementKind::anp;
  if (code >= 10) {
    spec.kind = hybrid::PartitionKind::linear_fraction;
    spec.linear_fraction = code >= 100 ? (code - 100) / 100.0 : (code - 10) / 10.0;
  }
  return hybrid::make_partition(m, spec);
}

material::NeoHookeanForm form(int code) {
  return code == 1 || code == 4 ? material::NeoHookeanForm::decoupled : material::NeoHookeanForm::paper;
}

fem::LinearForces linear_forces(int code) {
  return code == 5 ? fem::LinearForces::per_element : fem::LinearForces::assembled;
}

fem::ElementSet element_set(int code, int tile_nodes = 128,
                            fem::LinearPrecision precision = fem::LinearPrecision::double_precision) {
  fem::ElementSet set(paper_mesh(), partition(code), fem::Material::make(kPaper, form(code)), tile_nodes,
                      linear_forces(code));
  set.set_linear_precision(precision);
  return set;
}

// A deformed state: a 20 % shear with a 30° rotation, so the corotational polar decomposition
// does real work.
std::vector<double> deformed_state() {
  const auto& m = paper_mesh();
  Eigen::Matrix3d F;
  F << 1.0, 0.2, 0.0, 0.0, 0.95, 0.0, 0.0, 0.0, 1.05;
  F = Eigen::AngleAxisd(0.5, Eigen::Vector3d(0, 0, 1)).toRotationMatrix() * F;
  std::vector<double> u(3 * m.nodes.size());
  for (int i = 0; i < m.num_nodes(); ++i)
    for (int k = 0; k < 3; ++k) u[3 * i + k] = ((F - Eigen::Matrix3d::Identity()) * m.nodes[i])[k];
  return u;
}

// Explicit steps of one partition: steps/s, ns per element of each kind and per node.
void run_steps(benchmark::State& state, int code, int threads, bool skip_held_nodes,
               int energy_interval = kStepsPerIteration,
               fem::LinearPrecision precision = fem::LinearPrecision::double_precision) {
  const auto& m = paper_mesh();
  fem::ElementSet elements = element_set(code, 128, precision);
  dynamics::ExplicitOptions opt;
  opt.dt = 0.9 * dynamics::critical_time_step(m, kPaper).dt;
  opt.steps = kStepsPerIteration;
  opt.threads = threads;
  opt.energy_interval = energy_interval;
  opt.skip_held_nodes = skip_held_nodes;
  const dynamics::Scene scene = hybrid::default_bench_scene(m, 1000 * opt.dt);
  dynamics::ExplicitSolver solver(elements, dynamics::lumped_mass(m, kPaper.density), scene, opt);
  dynamics::ExplicitTiming last;
  for (auto _ : state) {
    const auto r = solver.run();
    benchmark::DoNotOptimize(r.displacement.data());
    last = r.timing;
  }
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kStepsPerIteration, benchmark::Counter::kIsRate);
  for (int k = 0; k < fem::kNumElementKinds; ++k)
    if (last.element_counts[k] > 0)
      state.counters[std::string("ns_per_") + fem::kind_name(static_cast<ElementKind>(k))] =
          last.ns_per_element(k, kStepsPerIteration);
  state.counters["ns_per_node"] = last.ns_per_node(m.num_nodes(), kStepsPerIteration);
}

void BM_Steps(benchmark::State& state) {
  run_steps(state, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), true);
}

// The same with an energy sample every 20 steps, so that an iteration is ten runs of the thread
// team (dynamics/parallel.hpp decides the team size per run, as in dhd_sim, whose runs end at
// each energy sample): the figures to compare 1 and 2 threads on a busy machine.
void BM_StepsSampled(benchmark::State& state) {
  run_steps(state, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), true, 20);
}
BENCHMARK(BM_StepsSampled)->ArgNames({"partition", "threads"})->ArgsProduct({{0, 15}, {1, 2}})->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void steps_args(benchmark::internal::Benchmark* b) {
  for (int threads : {1, 2})
    for (int code : {0, 1, 2, 3, 5, 15}) b->Args({code, threads});
  for (int code : {11, 12, 13, 14}) b->Args({code, 1});  // Table 1's shares of linear elements
}
BENCHMARK(BM_Steps)->Apply(steps_args)->ArgNames({"partition", "threads"})->UseRealTime()->Unit(benchmark::kMillisecond);

// 000 Table 1's speed-up: one thread, linear share r = (partition − 100) / 100 (the linear elements
// farthest from the top centre), the linear rows' values in double (single 0) or single precision
// (single 1). r = 0 is the all-TLED reference (no rows: precision does not apply).
void BM_HybridSpeedUp(benchmark::State& state) {
  run_steps(state, static_cast<int>(state.range(0)), 1, true, kStepsPerIteration,
            state.range(1) != 0 ? fem::LinearPrecision::single_precision : fem::LinearPrecision::double_precision);
}
void hybrid_args(benchmark::internal::Benchmark* b) {
  b->Args({100, 0});
  for (int code : {125, 150, 175, 200})
    for (int single : {0, 1}) b->Args({code, single});
}
BENCHMARK(BM_HybridSpeedUp)->Apply(hybrid_args)->ArgNames({"partition", "single"})->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The same steps with the held (fixed) nodes updated like the others (skip 0) and left out of
// the node update (skip 1, the engine's default): the bench scene fixes the bottom layer.
void BM_HeldNodes(benchmark::State& state) {
  run_steps(state, static_cast<int>(state.range(0)), 1, state.range(1) != 0);
}
BENCHMARK(BM_HeldNodes)->ArgNames({"partition", "skip"})->Args({2, 0})->Args({2, 1})->Args({0, 0})->Args({0, 1})
    ->UseRealTime()->Unit(benchmark::kMillisecond);

// One element phase over all elements of one kind, on a deformed state.
void BM_Kernel(benchmark::State& state) {
  const int code = static_cast<int>(state.range(0));
  fem::ElementSet elements = element_set(code);
  const std::vector<double> u = deformed_state();
  for (auto _ : state) {
    fem::KernelStats st;
    elements.compute(u.data(), st);
    benchmark::DoNotOptimize(st.min_j);
  }
  if (elements.assembled_linear()) state.counters["linear_blocks"] = elements.linear_rows().num_blocks();
  // Elements per second; nanoseconds per element = 1e9 / elements_per_s.
  state.counters["elements_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()) * paper_mesh().num_tets(),
                                                        benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Kernel)->ArgName("partition")->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Arg(4)->Arg(5)->Arg(15)->Unit(benchmark::kMicrosecond);

// The complete internal nodal forces from the displacements (element phase and the nodal sums
// of 000 eq. 23), all elements of one kind: the per-element cost the kinds compare by, since an
// element's corner forces are only useful once summed at the nodes.
void BM_NodalForces(benchmark::State& state) {
  const int code = static_cast<int>(state.range(0));
  fem::ElementSet elements = element_set(code);
  const std::vector<double> u = deformed_state();
  std::vector<double> f(u.size());
  for (auto _ : state) {
    fem::KernelStats st;
    elements.compute(u.data(), st);
    for (int i = 0; i < elements.num_nodes(); ++i) elements.gather(i, &f[3 * static_cast<std::size_t>(i)]);
    benchmark::DoNotOptimize(f.data());
  }
  state.counters["elements_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()) * paper_mesh().num_tets(),
                                                        benchmark::Counter::kIsRate);
}
BENCHMARK(BM_NodalForces)->ArgName("partition")->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Arg(4)->Arg(5)->Arg(15)->Unit(benchmark::kMicrosecond);

// The assembled linear rows of the paper mesh, all nodes once (as in BM_Kernel/partition:2), and
// the same number of row products over the first eighth of the nodes eight times, whose blocks
// stay in the L2 cache: the ratio tells how much of the row product is streaming the matrix.
// kernel 0: the engine's (the AVX-512 or AVX2 kernel where the build has one), 1: the plain loops.
void BM_LinearRows(benchmark::State& state) {
  const int repeats = static_cast<int>(state.range(0));
  const auto kernel = state.range(1) == 0 ? fem::LinearStiffnessRows::Kernel::best : fem::LinearStiffnessRows::Kernel::portable;
  const auto& m = paper_mesh();
  const fem::LinearStiffnessRows rows(m, std::vector<ElementKind>(m.num_tets(), ElementKind::linear),
                                      fem::Material::make(kPaper, material::NeoHookeanForm::paper));
  const std::vector<double> u = deformed_state();
  std::vector<double> f(u.size());
  std::vector<int> nodes(m.num_nodes() / repeats);
  for (std::size_t a = 0; a < nodes.size(); ++a) nodes[a] = static_cast<int>(a);
  for (auto _ : state) {
    for (int r = 0; r < repeats; ++r)
      rows.multiply_rows(nodes.data(), nodes.data() + nodes.size(), u.data(), f.data(), kernel);
    benchmark::DoNotOptimize(f.data());
  }
  state.counters["blocks"] = rows.num_blocks();
}
BENCHMARK(BM_LinearRows)->ArgNames({"repeats", "kernel"})->Args({1, 0})->Args({8, 0})->Args({1, 1})->Unit(benchmark::kMicrosecond);

// The memory floor of the assembled rows: reading, once, as many values as the rows store (nine
// doubles and one neighbour index per block, and the row starts) with 8-wide sums and no other
// work. No product of the stored matrix can stream it faster.
void BM_LinearRowsMemoryFloor(benchmark::State& state) {
  const auto& m = paper_mesh();
  const fem::LinearStiffnessRows rows(m, std::vector<ElementKind>(m.num_tets(), ElementKind::linear),
                                      fem::Material::make(kPaper, material::NeoHookeanForm::paper));
  // Four accumulators of four doubles: eight-wide generic vectors are spilled to the stack on
  // targets without 512-bit registers, which would measure the spills instead of the bytes.
  typedef double Vec4 __attribute__((vector_size(32)));
  typedef int Int8 __attribute__((vector_size(32)));
  const std::size_t blocks = rows.num_blocks();
  fem::AlignedVector<Vec4> values((9 * blocks + 3) / 4, Vec4{} + 1e-9);
  fem::AlignedVector<Int8> ints((blocks + m.num_nodes() + 1 + 7) / 8, Int8{} + 1);
  for (auto _ : state) {
    Vec4 s0{}, s1{}, s2{}, s3{};
    std::size_t q = 0;
    for (; q + 3 < values.size(); q += 4) {
      s0 += values[q];
      s1 += values[q + 1];
      s2 += values[q + 2];
      s3 += values[q + 3];
    }
    for (; q < values.size(); ++q) s0 += values[q];
    Int8 k{};
    for (const Int8& v : ints) k += v;
    benchmark::DoNotOptimize((s0 + s1) + (s2 + s3));
    benchmark::DoNotOptimize(k);
  }
  state.counters["bytes"] = static_cast<double>(values.size() * sizeof(Vec4) + ints.size() * sizeof(Int8));
}
BENCHMARK(BM_LinearRowsMemoryFloor)->Unit(benchmark::kMicrosecond);

// The largest difference between forces `f` and the engine's rows' product at `u`, relative to
// the largest of the latter: what another evaluation of the rows changes.
double difference_to_rows(const fem::LinearStiffnessRows& rows, const std::vector<double>& u,
                          const std::vector<double>& f) {
  std::vector<int> nodes(u.size() / 3);
  for (std::size_t a = 0; a < nodes.size(); ++a) nodes[a] = static_cast<int>(a);
  std::vector<double> exact(u.size());
  rows.multiply_rows(nodes.data(), nodes.data() + nodes.size(), u.data(), exact.data());
  double largest = 0, difference = 0;
  for (std::size_t q = 0; q < f.size(); ++q) {
    largest = std::max(largest, std::abs(exact[q]));
    difference = std::max(difference, std::abs(f[q] - exact[q]));
  }
  return difference / largest;
}

// What single-precision stiffness values buy (LinearPrecision::single_precision, the engine's
// solver.linear_precision "single"): the engine's kernel over the same blocks with each value
// stored as a float (the first eight of a block in 32 bytes, widened by one conversion), so the
// rows stream 45 % of the bytes. Counter: the largest force difference to the double-precision
// rows relative to the largest force (the price in accuracy).
void BM_LinearRowsSingleValues(benchmark::State& state) {
  const auto& m = paper_mesh();
  const fem::LinearStiffnessRows rows(m, std::vector<ElementKind>(m.num_tets(), ElementKind::linear),
                                      fem::Material::make(kPaper, material::NeoHookeanForm::paper));
  fem::LinearStiffnessRows single = rows;
  single.set_precision(fem::LinearPrecision::single_precision);
  std::vector<int> nodes(m.num_nodes());
  for (int a = 0; a < m.num_nodes(); ++a) nodes[a] = a;
  const std::vector<double> u = deformed_state();
  std::vector<double> f(u.size());
  for (auto _ : state) {
    single.multiply_rows(nodes.data(), nodes.data() + nodes.size(), u.data(), f.data());
    benchmark::DoNotOptimize(f.data());
  }
  const double blocks = rows.num_blocks();
  state.counters["max_rel_force_error"] = difference_to_rows(rows, u, f);
  state.counters["bytes"] = blocks * (9 * sizeof(float) + sizeof(int)) + (m.num_nodes() + 1) * sizeof(int);
}
BENCHMARK(BM_LinearRowsSingleValues)->Unit(benchmark::kMicrosecond);


#ifdef SOFTSIM_ROWS_AVX512
// The other way to vectorise the rows, measured against the engine's: eight rows at once, one
// per lane (rows grouped by length, a group padded to its longest row with zero blocks), the
// k-th block of each row per step, its neighbours' displacements fetched by three hardware
// gathers, the nine values of the eight blocks stored as nine 8-wide vectors. Nine multiply-adds
// per eight blocks instead of two per block, and no row sums, but the gathers set the pace on
// this machine. Counters: the force difference to the engine's rows relative to the largest
// force (a check that it computes the same product) and the share of padding.
void BM_LinearRowsInLanes(benchmark::State& state) {
  const auto& m = paper_mesh();
  const fem::LinearStiffnessRows rows(m, std::vector<ElementKind>(m.num_tets(), ElementKind::linear),
                                      fem::Material::make(kPaper, material::NeoHookeanForm::paper));
  const int n = m.num_nodes(), groups = (n + 7) / 8;
  std::vector<int> order(n);
  for (int a = 0; a < n; ++a) order[a] = a;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return rows.row_blocks(a) > rows.row_blocks(b); });
  order.resize(8 * static_cast<std::size_t>(groups), -1);
  std::vector<int> first_step(groups + 1, 0);
  for (int g = 0; g < groups; ++g) first_step[g + 1] = first_step[g] + rows.row_blocks(order[8 * g]);
  const std::size_t steps = first_step[groups];
  fem::AlignedVector<double> values(72 * steps, 0.0);
  fem::AlignedVector<int> neighbour(8 * steps, 0);
  std::size_t padding = 0;
  for (int g = 0; g < groups; ++g)
    for (int k = 0; k < first_step[g + 1] - first_step[g]; ++k)
      for (int l = 0; l < 8; ++l) {
        const int a = order[8 * g + l];
        const std::size_t s = first_step[g] + k;
        if (a < 0 || k >= rows.row_blocks(a)) {
          ++padding;
          continue;
        }
        const int p = rows.first_block(a) + k;
        neighbour[8 * s + l] = 3 * rows.column_node(p);
        for (int q = 0; q < 9; ++q) values[72 * s + 8 * q + l] = rows.value(p, q / 3, q % 3);
      }
  const std::vector<double> u = deformed_state();
  std::vector<double> f(u.size());
  for (auto _ : state) {
    for (int g = 0; g < groups; ++g) {
      __m512d sum[3] = {_mm512_setzero_pd(), _mm512_setzero_pd(), _mm512_setzero_pd()};
      for (std::size_t s = first_step[g]; s < static_cast<std::size_t>(first_step[g + 1]); ++s) {
        const __m256i at = _mm256_load_si256(reinterpret_cast<const __m256i*>(&neighbour[8 * s]));
        const __m512d x[3] = {_mm512_i32gather_pd(at, u.data(), 8), _mm512_i32gather_pd(at, u.data() + 1, 8),
                              _mm512_i32gather_pd(at, u.data() + 2, 8)};
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) sum[r] = _mm512_fmadd_pd(_mm512_load_pd(&values[72 * s + 8 * (3 * r + c)]), x[c], sum[r]);
      }
      alignas(64) double out[3][8];
      for (int r = 0; r < 3; ++r) _mm512_store_pd(out[r], sum[r]);
      for (int l = 0; l < 8 && order[8 * g + l] >= 0; ++l)
        for (int r = 0; r < 3; ++r) f[3 * order[8 * g + l] + r] = out[r][l];
    }
    benchmark::DoNotOptimize(f.data());
  }
  state.counters["max_rel_force_difference"] = difference_to_rows(rows, u, f);
  state.counters["padding_share"] = static_cast<double>(padding) / (8.0 * steps);
}
BENCHMARK(BM_LinearRowsInLanes)->Unit(benchmark::kMicrosecond);
#endif

// The literal reading of "a precomputed 12 × 12 stiffness block times the element's
// displacements" for linear elements, for comparison with BM_Kernel/partition:2 (the same
// forces from the shape gradients): 144 stored values per element instead of 10.
void BM_LinearBlockKernel(benchmark::State& state) {
  const auto& m = paper_mesh();
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  const int ne = m.num_tets();
  std::vector<double> blocks(static_cast<std::size_t>(ne) * 144);
  std::vector<int> nodes(static_cast<std::size_t>(ne) * 4);
  const fem::Corners zero{};
  for (int e = 0; e < ne; ++e) {
    const fem::ElementMatrix K = fem::element_tangent(mat, ElementKind::linear, fem::tet_shape(m, e), zero);
    for (int r = 0; r < 12; ++r)
      for (int c = 0; c < 12; ++c) blocks[static_cast<std::size_t>(e) * 144 + 12 * r + c] = K(r, c);
    for (int a = 0; a < 4; ++a) nodes[4 * e + a] = 3 * m.tets[e][a];
  }
  std::vector<double> u(3 * m.nodes.size(), 1e-4), out(static_cast<std::size_t>(ne) * 12);
  for (std::size_t q = 0; q < u.size(); ++q) u[q] = 1e-4 * static_cast<double>(q % 17);
  for (auto _ : state) {
    for (int e = 0; e < ne; ++e) {
      double ue[12];
      for (int a = 0; a < 4; ++a)
        for (int k = 0; k < 3; ++k) ue[3 * a + k] = u[nodes[4 * e + a] + k];
      const double* K = &blocks[static_cast<std::size_t>(e) * 144];
      for (int r = 0; r < 12; ++r) {
        double f = 0;
        for (int c = 0; c < 12; ++c) f += K[12 * r + c] * ue[c];
        out[static_cast<std::size_t>(e) * 12 + r] = f;
      }
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["elements_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * ne, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LinearBlockKernel)->Unit(benchmark::kMicrosecond);

// The memory floor of any element kernel with the engine's data path: the same loads (4 node
// offsets, 12 gathered displacements, 9 gradients and the volume per element) and the same 12
// component-major stores, with a single add per output in place of the mechanics. Its rate
// bounds what a cheaper linear element could reach without a different data layout: compare
// with BM_Kernel/partition:2 (linear) and partition:0 (TLED).
void BM_MemoryFloorKernel(benchmark::State& state) {
  const auto& m = paper_mesh();
  const int ne = m.num_tets();
  const int stride = (ne + 7) / 8 * 8;
  std::array<std::vector<int>, 4> n;
  std::array<std::vector<double>, 10> g;  // 9 gradients and the volume
  for (auto& v : n) v.assign(stride, 0);
  for (auto& v : g) v.assign(stride, 0.0);
  for (int e = 0; e < ne; ++e) {
    const fem::TetShape sh = fem::tet_shape(m, e);
    for (int a = 0; a < 4; ++a) n[a][e] = 3 * m.tets[e][a];
    for (int a = 1; a < 4; ++a)
      for (int c = 0; c < 3; ++c) g[3 * (a - 1) + c][e] = sh.grad[a][c];
    g[9][e] = sh.volume;
  }
  std::vector<double> u(3 * m.nodes.size()), out(static_cast<std::size_t>(12) * stride);
  for (std::size_t q = 0; q < u.size(); ++q) u[q] = 1e-4 * static_cast<double>(q % 17);
  const int* __restrict n0 = n[0].data();
  const int* __restrict n1 = n[1].data();
  const int* __restrict n2 = n[2].data();
  const int* __restrict n3 = n[3].data();
  const double* __restrict uu = u.data();
  double* __restrict o = out.data();
  for (auto _ : state) {
#if defined(SOFTSIM_HAVE_OPENMP)
#pragma omp simd
#endif
    for (int k = 0; k < stride; ++k) {
      const int a[4] = {n0[k], n1[k], n2[k], n3[k]};
      for (int c = 0; c < 12; ++c) o[static_cast<std::size_t>(c) * stride + k] = uu[a[c / 3] + c % 3] + g[c % 10][k];
    }
    benchmark::DoNotOptimize(o);
    benchmark::ClobberMemory();
  }
  state.counters["elements_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * ne, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MemoryFloorKernel)->Unit(benchmark::kMicrosecond);

}  // namespace
