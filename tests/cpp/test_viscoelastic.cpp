// The Prony-series visco-hyperelastic law (material/viscoelastic.hpp) in the explicit engine:
// a step strain held relaxes the forces exactly as the series predicts, its limits (g → 0,
// τ → ∞, τ → 0) are the base, instantaneous and relaxed laws, a closed strain cycle dissipates
// energy, the internal variables restart with reset() and stay with the elements a cut leaves,
// and a held press settles on the static solution of the relaxed law.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <nlohmann/json.hpp>

#include "softsim/fem/element_set.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/hybrid/dhd_scene.hpp"
#include "softsim/material/hyperelastic.hpp"
#include "softsim/material/viscoelastic.hpp"

#include "support/scenes.hpp"

using namespace softsim;
using fem::ElementKind;

namespace {

const material::NeoHookean kBase = material::NeoHookean::from(material::NeoHookeanForm::decoupled, test_scenes::kPaper);

material::Viscoelastic visco(std::vector<double> g, std::vector<double> tau, material::ElasticLaw base = kBase) {
  material::Viscoelastic v;
  v.base = base;
  v.terms = static_cast<int>(g.size());
  for (int i = 0; i < v.terms; ++i) {
    v.g[i] = g[i];
    v.tau[i] = tau[i];
  }
  return v;
}

std::vector<double> homogeneous(const mesh::TetMesh& m, const Eigen::Matrix3d& F) {
  std::vector<double> u(3 * m.num_nodes());
  for (int i = 0; i < m.num_nodes(); ++i)
    for (int k = 0; k < 3; ++k) u[3 * i + k] = ((F - Eigen::Matrix3d::Identity()) * m.nodes[i])[k];
  return u;
}

std::vector<double> nodal_forces(fem::ElementSet& set, const std::vector<double>& u, fem::StepClock clock = {}) {
  fem::KernelStats st;
  set.compute(u.data(), st, clock);
  std::vector<double> f(3 * set.num_nodes());
  for (int n = 0; n < set.num_nodes(); ++n) set.gather(n, f.data() + 3 * n);
  return f;
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

fem::ElementSet tled_set(const mesh::TetMesh& m, const material::HyperelasticLaw& law) {
  return fem::ElementSet(m, std::vector<ElementKind>(m.num_tets(), ElementKind::tled),
                         fem::Material::make(test_scenes::kPaper, law));
}

const mesh::TetMesh& block() {
  static const mesh::TetMesh m = test_scenes::cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  return m;
}

Eigen::Matrix3d step_strain() {
  Eigen::Matrix3d F;
  F << 1.15, 0.1, 0.0, 0.0, 0.92, 0.05, 0.02, 0.0, 0.97;
  return F;
}

}  // namespace

// A step strain applied at step 0 and held: S(tₙ) = S_vol + S_iso g(tₙ + Δt) with
// g(t) = g∞ + Σ gᵢ exp(−t/τᵢ) (the recursion's convention, viscoelastic.hpp), so the nodal
// forces are f_base − (1 − g(t)) f_iso, both from the elastic kernels.
TEST(Viscoelastic, HeldStepStrainRelaxesAsThePronySeries) {
  const auto& m = block();
  const material::Viscoelastic v = visco({0.3, 0.25}, {0.01, 0.2});
  fem::ElementSet relaxing = tled_set(m, v);
  fem::ElementSet base = tled_set(m, kBase);
  fem::ElementSet iso = tled_set(m, material::isochoric_part(kBase));
  const std::vector<double> u = homogeneous(m, step_strain());
  const std::vector<double> fb = nodal_forces(base, u), fi = nodal_forces(iso, u);
  const double dt = 1e-3, scale = max_abs(fb);
  for (int s = 0; s < 400; ++s) {
    const std::vector<double> f = nodal_forces(relaxing, u, {s, dt});
    const double t = (s + 1) * dt;
    const double g = v.long_term() + 0.3 * std::exp(-t / 0.01) + 0.25 * std::exp(-t / 0.2);
    double err = 0;
    for (std::size_t q = 0; q < f.size(); ++q) err = std::max(err, std::abs(f[q] - (fb[q] - (1.0 - g) * fi[q])));
    ASSERT_LT(err, 1e-12 * scale) << "step " << s;
  }
  // Forces of a step computed again (start-up acceleration, reactions) do not advance the state.
  const std::vector<double> again = nodal_forces(relaxing, u, {399, dt});
  EXPECT_EQ(again, nodal_forces(relaxing, u, {399, dt}));
}

TEST(Viscoelastic, LimitsAreTheBaseInstantaneousAndRelaxedLaws) {
  const auto& m = block();
  fem::ElementSet base = tled_set(m, kBase);
  fem::ElementSet no_weight = tled_set(m, visco({0.0, 0.0}, {0.01, 0.1}));
  fem::ElementSet slow = tled_set(m, visco({0.4}, {1e300}));
  fem::ElementSet fast = tled_set(m, visco({0.4}, {1e-300}));
  fem::ElementSet relaxed_static = tled_set(m, visco({0.4}, {0.05}));  // its stateless (relaxed) law
  fem::ElementSet iso = tled_set(m, material::isochoric_part(kBase));
  const double dt = 1e-3;
  const double scale = max_abs(nodal_forces(base, homogeneous(m, step_strain())));  // round-off's scale
  for (int s = 0; s < 50; ++s) {
    Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + (0.02 * s / 50.0) * (step_strain() - Eigen::Matrix3d::Identity());
    const std::vector<double> u = homogeneous(m, F);
    // (The base's own kernel is the hand-vectorised neo-Hookean one: equal to round-off.)
    const std::vector<double> fb = nodal_forces(base, u);
    const auto near = [&](const std::vector<double>& f) {
      double err = 0;
      for (std::size_t q = 0; q < f.size(); ++q) err = std::max(err, std::abs(f[q] - fb[q]));
      return err <= 1e-14 * scale;
    };
    EXPECT_TRUE(near(nodal_forces(no_weight, u, {s, dt})));  // g = 0: the base law
    EXPECT_TRUE(near(nodal_forces(slow, u, {s, dt})));       // τ → ∞: the instantaneous law
    const std::vector<double> fi = nodal_forces(iso, u);
    const std::vector<double> ff = nodal_forces(fast, u, {s, dt});
    double err = 0;
    for (std::size_t q = 0; q < ff.size(); ++q) err = std::max(err, std::abs(ff[q] - (fb[q] - 0.4 * fi[q])));
    EXPECT_LE(err, 1e-14 * scale);  // τ → 0: relaxed at once
    // Without a clock (dt = 0) the state does not move: zero, the instantaneous law.
    EXPECT_TRUE(near(nodal_forces(relaxed_static, u)));
  }
  // Per material point, g = 0 and τ → ∞ leave the Prony tensors exactly zero: the base's P (to
  // round-off: P is formed as F (S_iso + S_vol), the base as its own P).
  for (const material::Viscoelastic& v : {visco({0.0, 0.0}, {0.01, 0.1}), visco({0.4}, {1e300})}) {
    double state[12] = {};
    const material::PronyStep step = material::prony_step(v, dt);
    for (int s = 0; s < 10; ++s) {
      const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + (0.1 * s) * (step_strain() - Eigen::Matrix3d::Identity());
      const Eigen::Matrix3d P = material::relaxed_first_piola(v, step, F, state, state);
      const Eigen::Matrix3d Pb = material::first_piola(kBase, F);
      EXPECT_LT((P - Pb).norm(), 1e-14 * kBase.bulk) << s;
      for (double a : state) EXPECT_EQ(a, 0.0);
    }
  }
  // The stateless law (static solver, outputs) is the relaxed one: P∞ = P_base − (1 − g∞) P_iso.
  const material::Viscoelastic v = visco({0.4}, {0.05});
  const Eigen::Matrix3d F = step_strain();
  const Eigen::Matrix3d expected = material::first_piola(kBase, F) - 0.4 * material::first_piola(material::isochoric_part(kBase), F);
  EXPECT_LT((material::first_piola(v, F) - expected).norm(), 1e-12 * expected.norm());
}

// A closed strain cycle F(t) = I + sin²(πt/T) H, then held at I until relaxed: the work done on
// the material, ∫ P : dF, is what it dissipated (W and the Prony tensors are back to zero). It is
// positive for g > 0 and zero (to the quadrature's error) for the elastic law.
TEST(Viscoelastic, AClosedStrainCycleDissipatesEnergy) {
  Eigen::Matrix3d H;
  H << 0.2, 0.1, 0.0, 0.05, -0.1, 0.0, 0.0, 0.03, -0.05;
  for (double period : {0.005, 0.05, 0.5}) {
    for (double g : {0.0, 0.5}) {
      const material::Viscoelastic v = visco({g}, {0.05});
      const int n = 4000;
      const double dt = period / n;
      const material::PronyStep step = material::prony_step(v, dt);
      double state[6] = {0, 0, 0, 0, 0, 0};
      Eigen::Matrix3d F_prev = Eigen::Matrix3d::Identity();
      Eigen::Matrix3d P_prev = material::relaxed_first_piola(v, step, F_prev, state, state);
      double work = 0, scale = 0;
      for (int k = 1; k <= n; ++k) {
        const double s = std::sin(M_PI * k / n);
        const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + s * s * H;
        const Eigen::Matrix3d P = material::relaxed_first_piola(v, step, F, state, state);
        work += 0.5 * ((P + P_prev).array() * (F - F_prev).array()).sum();
        scale += 0.5 * std::abs(((P + P_prev).array() * (F - F_prev).array()).sum());
        F_prev = F;
        P_prev = P;
      }
      if (g == 0) EXPECT_NEAR(work, 0.0, 1e-6 * scale) << "period " << period;
      else EXPECT_GT(work, 1e-3 * scale) << "period " << period;
    }
  }
}

TEST(Viscoelastic, StateRestartsWithResetAndStaysWithTheElementsACutLeaves) {
  const auto& m = block();
  fem::ElementSet set = tled_set(m, visco({0.3}, {0.01}));
  ASSERT_TRUE(set.has_law_state());
  const std::vector<double> u = homogeneous(m, step_strain());
  for (int s = 0; s < 5; ++s) nodal_forces(set, u, {s, 1e-3});
  std::vector<double> before;
  for (int e = 0; e < m.num_tets(); ++e)
    for (int c = 0; c < 6; ++c) before.push_back(set.law_state(4, set.slot_of(e), c));
  EXPECT_GT(max_abs(before), 0.0);
  set.remove_elements(m, {0, 7});
  for (int e = 0; e < m.num_tets(); ++e)
    for (int c = 0; c < 6; ++c) {
      const double now = set.law_state(4, set.slot_of(e), c);
      if (e == 0 || e == 7) EXPECT_EQ(now, 0.0);
      else EXPECT_EQ(now, before[6 * e + c]);
    }
  set.reset_law_state();
  for (int e = 0; e < m.num_tets(); ++e)
    for (int c = 0; c < 6; ++c) EXPECT_EQ(set.law_state(4, set.slot_of(e), c), 0.0);
}

namespace {

nlohmann::json press_config(const nlohmann::json& material, const std::string& solver) {
  nlohmann::json j = nlohmann::json::parse(R"({
    "mesh": "m",
    "damping": {"alpha": 60},
    "boundary": {"fixed": ["bottom"], "prescribed": [{"set": "top", "displacement": [0, 0, -0.002], "ramp_time": 0.02}]}
  })");
  j["material"] = material;
  j["solver"] = solver == "static" ? nlohmann::json{{"kind", "static"}, {"increments", 4}}
                                   : nlohmann::json{{"kind", "explicit"}, {"steps", 6000}, {"energy_interval", 100}};
  return j;
}

}  // namespace

// The engine end to end: reset() replays a run bit for bit; a press held for many relaxation
// times settles on the static solve of the relaxed law (not the instantaneous one), after
// reaction forces that fell from above it.
TEST(Viscoelastic, HeldPressSettlesOnTheRelaxedStaticSolution) {
  auto mesh = std::make_shared<const mesh::TetMesh>(test_scenes::cuboid(2, 2, 2, 0.02, 0.02, 0.02));
  const nlohmann::json material = {{"model", "visco_neo_hookean"}, {"E", 5000}, {"nu", 0.35}, {"density", 1000},
                                   {"prony", {{"g", {0.4, 0.2}}, {"tau", {0.005, 0.03}}}}};
  hybrid::DhdScene scene(mesh, hybrid::read_dhd_config(io::JsonReader(press_config(material, "explicit"), "c.json"), *mesh));
  const int steps = static_cast<int>(std::ceil(0.5 / scene.dt()));
  scene.step(200);
  const std::vector<double> early(scene.displacement(), scene.displacement() + 3 * mesh->num_nodes());
  const int top = scene.constraint_index("prescribed top");
  const double early_force = scene.reactions()[top].z();
  scene.reset();
  scene.step(200);
  EXPECT_EQ(std::vector<double>(scene.displacement(), scene.displacement() + 3 * mesh->num_nodes()), early);
  scene.step(steps - 200);
  const double late_force = scene.reactions()[top].z();

  hybrid::DhdScene relaxed(mesh, hybrid::read_dhd_config(io::JsonReader(press_config(material, "static"), "s.json"), *mesh));
  const double static_force = relaxed.solve_static().reactions[top].z();
  nlohmann::json elastic = material;
  elastic.erase("prony");
  elastic["model"] = "neo_hookean_decoupled";
  hybrid::DhdScene instantaneous(mesh, hybrid::read_dhd_config(io::JsonReader(press_config(elastic, "static"), "e.json"), *mesh));
  const double elastic_force = instantaneous.solve_static().reactions[top].z();
  EXPECT_NEAR(late_force, static_force, 1e-3 * std::abs(static_force));
  EXPECT_GT(std::abs(elastic_force), 1.5 * std::abs(static_force));  // g∞ = 0.4 of the isochoric part
  EXPECT_GT(std::abs(early_force), std::abs(static_force));
}
