// What a tissue law costs per element in the explicit engine's element phase, on paper 000's
// 14450-tet cuboid, all TLED, at a 20 % shear with a 30° rotation:
//   BM_LawKernel/law:0  decoupled neo-Hookean (its hand-vectorised kernel, no state: the
//                       reference a law without internal variables or fibres keeps)
//                law:1  Mooney–Rivlin (the generic kernel)
//                law:2  transversely isotropic, one fibre for all elements
//                law:3  transversely isotropic, a fibre per element (read per slot)
//                law:4  decoupled neo-Hookean with a two-term Prony series (6 × 2 internal
//                       variables per element read and written every step)
// Counter elements_per_s (CPU time): 1e9 / elements_per_s is the cost per element in ns.
#include <benchmark/benchmark.h>

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

void BM_LawKernel(benchmark::State& state) {
  const auto& m = paper_mesh();
  fem::ElementSet elements(m, std::vector<fem::ElementKind>(m.num_tets(), fem::ElementKind::tled),
                           material_of(static_cast<int>(state.range(0))));
  const std::vector<double> u = deformed_state();
  int step = 0;
  for (auto _ : state) {
    fem::KernelStats st;
    elements.compute(u.data(), st, fem::StepClock{step++, 1e-4});
    benchmark::DoNotOptimize(st.min_j);
  }
  // Elements per second; nanoseconds per element = 1e9 / elements_per_s.
  state.counters["elements_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * m.num_tets(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LawKernel)->ArgName("law")->DenseRange(0, 4)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
