// What a tissue law costs per element in the explicit engine's element phase, on paper 000's
// 14450-tet cuboid, all elements of one kind (kind:0 TLED, kind:1 ANP, whose nodal-pressure
// pre-pass is included), at a 20 % shear with a 30° rotation:
//   law:0  decoupled neo-Hookean (its hand-vectorised kernel: the reference)
//   law:1  Mooney–Rivlin (fem/invariant_kernels.hpp)
//   law:2  transversely isotropic, one fibre for all elements
//   law:3  transversely isotropic, a fibre per element (read per slot)
//   law:4  decoupled neo-Hookean with a two-term Prony series (6 × 2 internal variables per
//          element read and written every step, fused into the element pass)
//   law:5  Ogden, one term (α = 6.5; fem/ogden_kernels.hpp)
//   law:6  Ogden, three terms
//   law:7  stable neo-Hookean (fem/stable_kernels.hpp)
//   law:8  neo-Hookean, paper form
// BM_SmallStrainKernel/kind:2 linear (the assembled rows' product, per linear element), kind:3
// corotational: law-independent, for scale.
// Counter ns_per_element (CPU time per element and step).
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <memory>

#include "bench/paper_mesh.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/material/hyperelastic.hpp"
#include "softsim/mesh/cuboid.hpp"

using namespace softsim;

namespace {

using bench::kPaper;
using bench::paper_mesh;

fem::Material material_of(int code) {
  const material::NeoHookean nh = material::NeoHookean::from(material::NeoHookeanForm::decoupled, kPaper);
  const material::TransverselyIsotropic ti{nh.mu, 2.0 * nh.mu, nh.bulk, Eigen::Vector3d(1, 1, 0).normalized()};
  switch (code) {
    case 1: return fem::Material::make(kPaper, material::MooneyRivlin{0.35 * nh.mu, 0.15 * nh.mu, nh.bulk});
    case 2: return fem::Material::make(kPaper, ti);
    case 3: {
      fem::Material m = fem::Material::make(kPaper, ti);
      auto fibres = std::make_shared<std::vector<Eigen::Vector3d>>();
      for (int e = 0; e < paper_mesh().num_tets(); ++e)
        fibres->push_back(Eigen::Vector3d(std::cos(0.01 * e), std::sin(0.01 * e), 0.0));
      m.fibres = fibres;
      return m;
    }
    case 4: {
      material::Viscoelastic v;
      v.base = nh;
      v.terms = 2;
      v.g = {0.3, 0.2};
      v.tau = {0.01, 0.1};
      return fem::Material::make(kPaper, v);
    }
    case 5:
    case 6: {
      material::Ogden o;
      o.terms = code == 5 ? 1 : 3;
      o.mu = code == 5 ? std::array<double, 3>{nh.mu * 2.0 / 6.5, 0, 0} : std::array<double, 3>{1200.0, -300.0, 40.0};
      o.alpha = {6.5, -4.2, 1.3};
      o.bulk = nh.bulk;
      return fem::Material::make(kPaper, o);
    }
    case 7: return fem::Material::make(kPaper, material::StableNeoHookean::from(kPaper));
    case 8: return fem::Material::make(kPaper, material::NeoHookean::from(material::NeoHookeanForm::paper, kPaper));
    default: return fem::Material::make(kPaper, nh);
  }
}

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

const fem::ElementKind kKinds[] = {fem::ElementKind::tled, fem::ElementKind::anp, fem::ElementKind::linear,
                                   fem::ElementKind::corotational};

void run_kernel(benchmark::State& state, int law, fem::ElementKind kind) {
  const auto& m = paper_mesh();
  fem::ElementSet elements(m, std::vector<fem::ElementKind>(m.num_tets(), kind), material_of(law));
  const std::vector<double> u = deformed_state();
  int step = 0;
  for (auto _ : state) {
    fem::KernelStats st;
    elements.compute(u.data(), st, fem::StepClock{step++, 1e-4});
    benchmark::DoNotOptimize(st.min_j);
  }
  // CPU time per element and step.
  state.counters["ns_per_element"] = benchmark::Counter(static_cast<double>(state.iterations()) * m.num_tets() * 1e-9,
                                                        benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_LawKernel(benchmark::State& state) {
  run_kernel(state, static_cast<int>(state.range(0)), kKinds[state.range(1)]);
}
BENCHMARK(BM_LawKernel)->ArgNames({"law", "kind"})->ArgsProduct({benchmark::CreateDenseRange(0, 8, 1), {0, 1}})
    ->Unit(benchmark::kMicrosecond);

void BM_SmallStrainKernel(benchmark::State& state) { run_kernel(state, 0, kKinds[state.range(0)]); }
BENCHMARK(BM_SmallStrainKernel)->ArgName("kind")->DenseRange(2, 3)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
