// Cutting by separation along faces (019): which faces open and which nodes split, the engine's
// local update against a full set-up on the cut mesh, mass and momentum, a patch test on the cut
// mesh, a cut that opens nothing, a through cut (two pieces, the free one in exact free fall),
// stability after a cut under load, and the config's checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "softsim/cutting/live_mesh.hpp"
#include "softsim/cutting/pieces.hpp"
#include "softsim/cutting/separation.hpp"
#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/dynamics/spectral_step.hpp"
#include "softsim/dynamics/stable_step.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/hybrid/dhd_scene.hpp"
#include "softsim/io/errors.hpp"
#include "support/cut_scenes.hpp"
#include "support/fields.hpp"
#include "support/scenes.hpp"

using namespace softsim;
using fem::ElementKind;
using test_scenes::cuboid;
using test_scenes::kPaper;

namespace {

// A blade across the 4 cm cuboid at x = 2.1 cm, from above its top down to height `bottom`.
cutting::BladeSweep across(double bottom) {
  cutting::BladeSweep s;
  s.a0 = Eigen::Vector3d(0.021, -0.01, 0.05);
  s.b0 = Eigen::Vector3d(0.021, 0.05, 0.05);
  s.a1 = Eigen::Vector3d(0.021, -0.01, bottom);
  s.b1 = Eigen::Vector3d(0.021, 0.05, bottom);
  return s;
}

std::vector<ElementKind> mixed_kinds(int n) {
  std::vector<ElementKind> k(n);
  for (int e = 0; e < n; ++e) k[e] = static_cast<ElementKind>(e % fem::kNumElementKinds);
  return k;
}

struct CutMesh {
  mesh::TetMesh mesh;
  cutting::SeparationPlan plan;
};

// The plan of `sweep` on the reference mesh, and the mesh it leaves.
CutMesh separated(const mesh::TetMesh& m, const cutting::BladeSweep& sweep,
                  const std::function<bool(int)>& held = [](int) { return false; }) {
  CutMesh c{m, {}};
  cutting::FaceTopology topology(m);
  const auto crossed = cutting::elements_crossed(m, nullptr, sweep);
  c.plan = cutting::plan_separation(m, nullptr, sweep, crossed, topology, [](int) { return false; }, held);
  cutting::apply_separation(c.mesh, topology, c.plan);
  return c;
}

std::vector<fem::ElementSet::NodeCopy> copies_of(const cutting::SeparationPlan& plan) {
  std::vector<fem::ElementSet::NodeCopy> out;
  for (const auto& s : plan.splits) out.push_back({s.node, s.copy, s.elements});
  return out;
}

Eigen::Vector3d centroid(const mesh::TetMesh& m, int e) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int a : m.tets[e]) c += m.nodes[a];
  return 0.25 * c;
}

}  // namespace

TEST(Separation, SegmentCrossing) {
  const cutting::Triangle t = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)};
  EXPECT_TRUE(cutting::segment_crosses(Eigen::Vector3d(0.2, 0.2, -1), Eigen::Vector3d(0.2, 0.2, 1), t));
  EXPECT_FALSE(cutting::segment_crosses(Eigen::Vector3d(0.8, 0.8, -1), Eigen::Vector3d(0.8, 0.8, 1), t));  // beside
  EXPECT_FALSE(cutting::segment_crosses(Eigen::Vector3d(0.2, 0.2, 0.5), Eigen::Vector3d(0.2, 0.2, 1), t));  // short
  EXPECT_FALSE(cutting::segment_crosses(Eigen::Vector3d(-1, 0.2, 0), Eigen::Vector3d(1, 0.2, 0), t));  // in plane
  // An end on the plane counts as the normal's side: tested either way, a segment gets one answer.
  const Eigen::Vector3d on(0.2, 0.2, 0), below(0.2, 0.2, -1), above(0.2, 0.2, 1);
  EXPECT_TRUE(cutting::segment_crosses(on, below, t));
  EXPECT_TRUE(cutting::segment_crosses(below, on, t));
  EXPECT_FALSE(cutting::segment_crosses(on, above, t));
  EXPECT_FALSE(cutting::segment_crosses(above, on, t));
}

// A blade through the centroids of a regular mesh's elements (x = 2.5 mm into a 1 cm cell of the
// cuboid's split, where tetrahedron centroids lie) still opens the block.
TEST(Separation, ABladeThroughCentroidsStillOpens) {
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  cutting::BladeSweep s = across(0.015);
  for (auto* p : {&s.a0, &s.b0, &s.a1, &s.b1}) p->x() = 0.025;
  const CutMesh c = separated(m, s);
  EXPECT_GT(c.plan.faces.size(), 10u);
  EXPECT_GT(c.plan.splits.size(), 5u);
}

// The cut faces separate the elements on either side of the blade within its sweep: each cut
// face's elements lie on opposite sides of x = 2.1 cm, and down to the blade's depth every pair
// of face neighbours across that plane is cut. Nodes split only where the sheet separates their
// fans: on the blade's front (its lower edge, inside the block) none do.
TEST(Separation, FacesBetweenTheSidesOpenAndOnlyThoseNodesSplit) {
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const double bottom = 0.015;
  const CutMesh c = separated(m, across(bottom));
  ASSERT_GT(c.plan.faces.size(), 10u);
  ASSERT_GT(c.plan.splits.size(), 5u);
  for (const auto& [a, b] : c.plan.faces) {
    EXPECT_LT((centroid(m, a).x() - 0.021) * (centroid(m, b).x() - 0.021), 0.0);
    EXPECT_GT(std::max(centroid(m, a).z(), centroid(m, b).z()), bottom);
  }
  cutting::FaceTopology before(m);
  int across_above = 0;
  for (int e = 0; e < m.num_tets(); ++e)
    for (int f = 0; f < 4; ++f) {
      const int b = before.neighbour(e, f);
      if (b <= e) continue;
      const Eigen::Vector3d ca = centroid(m, e), cb = centroid(m, b);
      if ((ca.x() - 0.021) * (cb.x() - 0.021) < 0 && std::max(ca.z(), cb.z()) > bottom + 0.01 &&
          std::min(ca.z(), cb.z()) > bottom) {
        ++across_above;
        EXPECT_TRUE(std::binary_search(c.plan.faces.begin(), c.plan.faces.end(), std::array<int, 2>{e, b}))
            << e << " " << b;
      }
    }
  EXPECT_GT(across_above, 0);
  for (const auto& s : c.plan.splits) {
    EXPECT_GT(m.nodes[s.node].z(), bottom - 0.01 + 1e-12) << "a node below the blade's front split";
    EXPECT_FALSE(s.elements.empty());
  }
  // The copies sit at their nodes' places, the moved elements keep their volume, and the two
  // sides of every opened face joined the boundary.
  EXPECT_EQ(c.mesh.num_nodes(), m.num_nodes() + static_cast<int>(c.plan.splits.size()));
  for (const auto& s : c.plan.splits) EXPECT_EQ(c.mesh.nodes[s.copy], m.nodes[s.node]);
  for (int e = 0; e < m.num_tets(); ++e)
    EXPECT_DOUBLE_EQ(mesh::signed_volume(c.mesh, c.mesh.tets[e]), mesh::signed_volume(m, m.tets[e]));
  EXPECT_GT(c.mesh.boundary.size(), m.boundary.size());
  // The cut mesh's boundary is exactly what a fresh topology finds without neighbours.
  cutting::FaceTopology after(c.mesh);
  int open_faces = 0;
  for (int e = 0; e < c.mesh.num_tets(); ++e)
    for (int f = 0; f < 4; ++f) open_faces += after.neighbour(e, f) < 0;
  EXPECT_EQ(open_faces, static_cast<int>(c.mesh.boundary.size()));
  for (int e = 0; e < c.mesh.num_tets(); ++e)
    for (int f = 0; f < 4; ++f) EXPECT_EQ(after.neighbour(e, f) < 0, after.boundary_triangle(e, f) >= 0);
}

// The element set updated in place equals one built from scratch on the cut mesh (every kind,
// ANP's nodal volumes included), and the solver's masses equal the lumped masses of the cut mesh.
TEST(Separation, LocalUpdateEqualsAFullSetUpOnTheCutMesh) {
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::decoupled);
  const auto kinds = mixed_kinds(m.num_tets());
  const CutMesh c = separated(m, across(0.015));
  fem::ElementSet cut(m, kinds, mat, 32, fem::LinearForces::per_element);
  cut.split_nodes(c.mesh, copies_of(c.plan));
  EXPECT_EQ(cut.num_nodes(), c.mesh.num_nodes());
  fem::ElementSet fresh(c.mesh, kinds, mat, 32, fem::LinearForces::per_element);
  fem::ElementSet assembled(c.mesh, kinds, mat, 32, fem::LinearForces::assembled);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-1e-3, 1e-3);
  std::vector<double> u(3 * c.mesh.num_nodes());
  for (double& x : u) x = d(rng);
  for (int k = 0; k < fem::kNumElementKinds; ++k) {  // each kind alone first: a failure names it
    const std::vector<ElementKind> one(m.num_tets(), static_cast<ElementKind>(k));
    fem::ElementSet split(m, one, mat, 32, fem::LinearForces::per_element);
    split.split_nodes(c.mesh, copies_of(c.plan));
    fem::ElementSet built(c.mesh, one, mat, 32, fem::LinearForces::per_element);
    const auto fb = test_scenes::gathered_forces(built, u);
    EXPECT_LT(test_scenes::max_abs_diff(test_scenes::gathered_forces(split, u), fb), 1e-12 * test_scenes::max_abs(fb))
        << fem::kind_name(static_cast<ElementKind>(k));
  }
  const auto fa = test_scenes::gathered_forces(cut, u);
  const auto fb = test_scenes::gathered_forces(fresh, u);
  EXPECT_LT(test_scenes::max_abs_diff(fa, fb), 1e-12 * test_scenes::max_abs(fb));
  EXPECT_LT(test_scenes::max_abs_diff(fa, test_scenes::gathered_forces(assembled, u)), 1e-12 * test_scenes::max_abs(fb));
  // An assembled linear element cannot move: refused before anything changes.
  fem::ElementSet rows(m, kinds, mat, 32, fem::LinearForces::assembled);
  EXPECT_THROW(rows.split_nodes(c.mesh, copies_of(c.plan)), std::invalid_argument);
  EXPECT_EQ(rows.num_nodes(), m.num_nodes());

  dynamics::ExplicitOptions opt;
  opt.dt = 1e-4;
  fem::ElementSet set(m, kinds, mat, 32, fem::LinearForces::per_element);
  dynamics::ExplicitSolver solver(set, dynamics::lumped_mass(m, kPaper.density), dynamics::Scene{}, opt);
  solver.split_nodes(c.mesh, copies_of(c.plan));
  const auto expected = dynamics::lumped_mass(c.mesh, kPaper.density);
  ASSERT_EQ(solver.masses().size(), expected.size());
  double total = 0, total_before = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(solver.masses()[i], expected[i], 1e-14 * kPaper.density * 1e-6) << "node " << i;
    total += solver.masses()[i];
  }
  for (double x : dynamics::lumped_mass(m, kPaper.density)) total_before += x;
  EXPECT_NEAR(total, total_before, 1e-13 * total_before);
}

// An affine field gives zero internal force at every node off the cut mesh's boundary (the
// opened faces are boundary now), for every element kind.
TEST(Separation, PatchTestPassesOnTheCutMesh) {
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  const CutMesh c = separated(m, across(0.015));
  std::vector<char> on_cut(c.mesh.num_nodes(), 0);
  for (const auto& [a, b] : c.plan.faces)
    for (int e : {a, b})
      for (int node : c.mesh.tets[e]) on_cut[node] = 1;
  Eigen::Matrix3d H;
  H << 0.01, 0.002, -0.003, 0.001, -0.004, 0.002, 0.0, 0.003, 0.005;
  const auto u = test_scenes::affine_field(c.mesh, Eigen::Matrix3d::Identity() + H);
  const double scale = kPaper.youngs_modulus * 0.01 * 0.01 * 0.01;
  for (int k = 0; k < fem::kNumElementKinds; ++k) {
    const std::vector<ElementKind> kinds(m.num_tets(), static_cast<ElementKind>(k));
    fem::ElementSet set(m, kinds, mat, 32, fem::LinearForces::per_element);
    set.split_nodes(c.mesh, copies_of(c.plan));
    const auto f = test_scenes::gathered_forces(set, u);
    int checked = 0;
    for (int i : test_scenes::interior_nodes(c.mesh)) {
      if (on_cut[i]) continue;
      ++checked;
      for (int q = 0; q < 3; ++q) EXPECT_NEAR(f[3 * i + q], 0.0, 1e-10 * scale) << "kind " << k << ", node " << i;
    }
    EXPECT_GT(checked, 5);
  }
}

namespace {

nlohmann::json block_config(const std::string& cuts) {
  return nlohmann::json::parse(R"({
    "mesh": "m",
    "material": {"model": "neo_hookean_decoupled", "E": 5000, "nu": 0.35, "density": 1000},
    "boundary": {"fixed": ["x_min"]},
    "solver": {"kind": "explicit", "steps": 2000, "energy_interval": 100},
    "cuts": )" + cuts + "}");
}

}  // namespace

// A sweep beside the block opens nothing and changes nothing, bit for bit. A sweep right through
// the block fixed at x = 0 leaves two pieces; the free one, cut at rest before any step under
// gravity, falls freely: every one of its nodes moves by exactly −½ g t² (central differences are
// exact for a constant acceleration, and a rigid translation stresses nothing).
TEST(Separation, NothingOpenedChangesNothingAndAThroughCutFallsFree) {
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const auto mesh = std::make_shared<const mesh::TetMesh>(m);
  const auto run = [&](const std::string& cuts, bool gravity) {
    nlohmann::json j = block_config(cuts);
    if (gravity) j["boundary"]["gravity"] = {0, 0, -9.81};
    else j["boundary"]["prescribed"] = {{{"set", "x_max"}, {"displacement", {0, 0, -0.004}}, {"ramp_time", 0.05}}};
    const auto config = hybrid::read_dhd_config(io::JsonReader(j, "config.json"), m);
    auto scene = std::make_unique<hybrid::DhdScene>(mesh, config, std::vector<ElementKind>(m.num_tets(), ElementKind::tled));
    scene->run();
    return scene;
  };
  const auto plain = run(R"([])", false);
  // Set up for separation (a cut scheduled after the end), stepped by hand around a sweep that
  // passes beside the block.
  nlohmann::json j = block_config(R"([{"time": 10, "from": [[0.021, -0.01, 0.05], [0.021, 0.05, 0.05]],
                                      "to": [[0.021, -0.01, 0.02], [0.021, 0.05, 0.02]], "mode": "separate"}])");
  j["boundary"]["prescribed"] = {{{"set", "x_max"}, {"displacement", {0, 0, -0.004}}, {"ramp_time", 0.05}}};
  hybrid::DhdScene beside_scene(mesh, hybrid::read_dhd_config(io::JsonReader(j, "config.json"), m),
                                std::vector<ElementKind>(m.num_tets(), ElementKind::tled));
  beside_scene.step(1000);
  cutting::BladeSweep beside = across(0.015);
  for (auto* p : {&beside.a0, &beside.b0, &beside.a1, &beside.b1}) p->x() += 1.0;
  const auto ev0 = beside_scene.cut(beside, hybrid::CutMode::separate);
  EXPECT_EQ(ev0.faces, 0);
  beside_scene.step(1000);
  EXPECT_TRUE(beside_scene.cut_events().empty());
  const std::vector<double> a(plain->displacement(), plain->displacement() + 3 * m.num_nodes());
  const std::vector<double> b(beside_scene.displacement(), beside_scene.displacement() + 3 * m.num_nodes());
  EXPECT_EQ(a, b);
  EXPECT_EQ(beside_scene.num_nodes(), m.num_nodes());

  const auto fall = run(R"([{"time": 0, "from": [[0.021, -0.01, 0.05], [0.021, 0.05, 0.05]],
                              "to": [[0.021, -0.01, -0.01], [0.021, 0.05, -0.01]], "mode": "separate"}])", true);
  ASSERT_EQ(fall->cut_events().size(), 1u);
  const auto& ev = fall->cut_events()[0];
  EXPECT_EQ(ev.pieces, 2);
  EXPECT_EQ(ev.loose_pieces, 1);
  EXPECT_GT(ev.copies.size(), 20u);
  EXPECT_EQ(fall->num_nodes(), m.num_nodes() + static_cast<int>(ev.copies.size()));
  const auto pieces = cutting::find_pieces(fall->mesh(), [](int) { return false; }, [&](int node) {
    return node < m.num_nodes() && m.nodes[node].x() == 0.0;
  });
  ASSERT_EQ(pieces.loose.size(), 1u);
  const double t = fall->time();
  int free_nodes = 0;
  for (int i = 0; i < fall->num_nodes(); ++i) {
    if (pieces.node_piece[i] != pieces.loose[0]) continue;
    ++free_nodes;
    const double* u = fall->displacement() + 3 * i;
    EXPECT_NEAR(u[2], -0.5 * 9.81 * t * t, 1e-9 * 9.81 * t * t) << "node " << i;
    EXPECT_NEAR(u[0], 0.0, 1e-12);
  }
  EXPECT_GT(free_nodes, 20);
  double moved = 0;
  for (int i = 0; i < fall->num_nodes(); ++i)
    if (pieces.node_piece[i] != pieces.loose[0]) moved = std::max(moved, std::abs(fall->displacement()[3 * i + 2] + 0.5 * 9.81 * t * t));
  EXPECT_GT(moved, 1e-4);  // the held half hangs from its wall instead
}

// Under load the run after a separating cut stays stable: no energy is removed (separation keeps
// every element), the balance closes with damping only, and the step is not re-estimated down
// (each element keeps its own mass share at every corner).
TEST(Separation, RunAfterACutUnderLoadStaysStableAndRemovesNoEnergy) {
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const auto mesh = std::make_shared<const mesh::TetMesh>(m);
  const nlohmann::json j = test_scenes::pressed_block_cut("separate");
  const auto config = hybrid::read_dhd_config(io::JsonReader(j, "config.json"), m);
  EXPECT_TRUE(config.separates);
  hybrid::DhdScene scene(mesh, config, std::vector<ElementKind>(m.num_tets(), ElementKind::tled));
  const double dt0 = scene.dt();
  const auto r = scene.run();
  ASSERT_EQ(scene.cut_events().size(), 1u);
  const auto& ev = scene.cut_events()[0];
  EXPECT_GT(ev.faces, 0);
  EXPECT_GT(ev.held_nodes_kept, 0);  // the top's prescribed nodes on the cut stay whole
  EXPECT_TRUE(ev.report.elements.empty());
  EXPECT_EQ(r.step_history.back().dt, dt0);
  double peak = 0;
  for (const auto& s : r.energies) peak = std::max(peak, s.kinetic + s.strain);
  const auto& last = r.energies.back();
  EXPECT_EQ(last.removed, 0.0);
  EXPECT_LT(last.kinetic, 1e-6 * peak);
  EXPECT_GT(last.dissipated, 0.0);
  for (double x : r.displacement) ASSERT_TRUE(std::isfinite(x));
  EXPECT_EQ(r.displacement.size(), 3u * scene.num_nodes());
}

// With the step from power iteration, a cut (either kind) measures 2/ω_max again on the cut
// system: the same value as a power iteration on the cut mesh from scratch, and the run's step is
// lowered to safety × that value when it exceeds it; a requested step above it is a numerical
// failure naming the cut.
TEST(Separation, APowerIterationStepIsMeasuredAgainAfterACut) {
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const auto mesh = std::make_shared<const mesh::TetMesh>(m);
  for (const std::string mode : {"remove", "separate"}) {
    nlohmann::json j = nlohmann::json::parse(R"({
      "mesh": "m",
      "material": {"model": "neo_hookean_decoupled", "E": 5000, "nu": 0.35, "density": 1000},
      "boundary": {"fixed": ["bottom"]},
      "solver": {"kind": "explicit", "steps": 400, "critical_step": "power_iteration", "safety_factor": 1.0},
      "cuts": [{"time": 0.01, "from": [[0.021, -0.01, 0.05], [0.021, 0.05, 0.05]], "to": [[0.021, -0.01, 0.015], [0.021, 0.05, 0.015]]}]
    })");
    j["cuts"][0]["mode"] = mode;
    const std::vector<ElementKind> kinds(m.num_tets(), ElementKind::tled);
    hybrid::DhdScene scene(mesh, hybrid::read_dhd_config(io::JsonReader(j, "c.json"), m), kinds);
    const double before = scene.spectral_step()->dt;
    scene.run();
    ASSERT_EQ(scene.cut_events().size(), 1u) << mode;
    const auto& ev = scene.cut_events()[0];
    const auto live = cutting::live_mesh(scene.mesh(), kinds, [&](int e) { return scene.removed(e); });
    const double fresh =
        dynamics::power_iteration_step(live.mesh, live.kinds, scene.config().material, scene.config().scene).dt;
    EXPECT_NEAR(ev.stable_step, fresh, 1e-12 * fresh) << mode;
    EXPECT_LT(ev.stable_step, before) << mode;  // here the cut raised ω_max
    EXPECT_LE(scene.dt(), ev.stable_step * (1 + 1e-12)) << mode;  // the step followed at once
    EXPECT_GT(ev.step_check_seconds, 0.0);
    // A requested step between the two limits runs before the cut and fails at it.
    j["solver"].erase("critical_step");
    j["solver"]["critical_step"] = "power_iteration";
    j["solver"]["dt"] = 0.5 * (before + ev.stable_step);
    hybrid::DhdScene fixed(mesh, hybrid::read_dhd_config(io::JsonReader(j, "c.json"), m), kinds);
    try {
      fixed.run();
      ADD_FAILURE() << mode << ": a requested step above the cut system's limit ran on";
    } catch (const NumericalError& e) {
      EXPECT_NE(std::string(e.what()).find("cut at t"), std::string::npos) << e.what();
    }
  }
}

// The copies are updated after the mid-step barrier by whichever thread owns the last part: a
// separating run (all kinds, ANP's nodal pressures included) gives the same result bit for bit
// with 1 and 2 threads.
TEST(Separation, ASeparatingRunIsBitIdenticalForAnyThreadCount) {
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const auto mesh = std::make_shared<const mesh::TetMesh>(m);
  const auto run = [&](int threads) {
    nlohmann::json j = test_scenes::pressed_block_cut("separate", 800);
    j["solver"]["energy_interval"] = 200;
    j["threads"] = threads;
    hybrid::DhdScene scene(mesh, hybrid::read_dhd_config(io::JsonReader(j, "config.json"), m), mixed_kinds(m.num_tets()));
    const auto r = scene.run();
    EXPECT_EQ(scene.cut_events().size(), 1u);
    return r.displacement;
  };
  const auto one = run(1);
  EXPECT_GT(one.size(), 3u * m.num_nodes());
  EXPECT_EQ(run(2), one);
}

TEST(Separation, ASceneNotSetUpForItRefusesASeparatingCut) {
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  const nlohmann::json j = nlohmann::json::parse(R"({"mesh": "m", "solver": {"kind": "explicit", "steps": 10}})");
  hybrid::DhdScene scene(std::make_shared<const mesh::TetMesh>(m), hybrid::read_dhd_config(io::JsonReader(j, "c.json"), m));
  cutting::BladeSweep s;
  s.a0 = Eigen::Vector3d(0.011, -0.01, 0.03);
  s.b0 = Eigen::Vector3d(0.011, 0.03, 0.03);
  s.a1 = Eigen::Vector3d(0.011, -0.01, 0.005);
  s.b1 = Eigen::Vector3d(0.011, 0.03, 0.005);
  EXPECT_THROW(scene.cut(s, hybrid::CutMode::separate), InputError);
  EXPECT_EQ(scene.num_nodes(), m.num_nodes());
}
