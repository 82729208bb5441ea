// Cutting by element removal (019): the blade's geometry, the engine's local update against a
// full set-up on the cut mesh, mass bookkeeping, a patch test on what is left, a cut that
// touches nothing, pieces, stability after a cut, and the config's checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "softsim/cutting/blade.hpp"
#include "softsim/cutting/element_grid.hpp"
#include "softsim/cutting/pieces.hpp"
#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/dynamics/lumped_mass.hpp"
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

// The mesh without the listed elements (same nodes, same node numbers).
mesh::TetMesh without(const mesh::TetMesh& m, const std::vector<int>& removed) {
  mesh::TetMesh out = m;
  out.tets.clear();
  for (int e = 0; e < m.num_tets(); ++e)
    if (!std::binary_search(removed.begin(), removed.end(), e)) out.tets.push_back(m.tets[e]);
  out.element_tags.clear();
  return out;
}

std::vector<ElementKind> kinds_without(const std::vector<ElementKind>& k, const std::vector<int>& removed) {
  std::vector<ElementKind> out;
  for (int e = 0; e < static_cast<int>(k.size()); ++e)
    if (!std::binary_search(removed.begin(), removed.end(), e)) out.push_back(k[e]);
  return out;
}

// Every kind, mixed through the mesh.
std::vector<ElementKind> mixed_kinds(int n) {
  std::vector<ElementKind> k(n);
  for (int e = 0; e < n; ++e) k[e] = static_cast<ElementKind>(e % fem::kNumElementKinds);
  return k;
}

// A blade across the top of the 4 cm cuboid, at x = 2.1 cm, pushed from above down to depth `depth`.
cutting::BladeSweep across_top(double depth) {
  cutting::BladeSweep s;
  s.a0 = Eigen::Vector3d(0.021, -0.01, 0.05);
  s.b0 = Eigen::Vector3d(0.021, 0.05, 0.05);
  s.a1 = Eigen::Vector3d(0.021, -0.01, 0.04 - depth);
  s.b1 = Eigen::Vector3d(0.021, 0.05, 0.04 - depth);
  return s;
}

}  // namespace

TEST(Blade, CrossingIsInteriorOverlapOnly) {
  const cutting::Tetrahedron t = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                  Eigen::Vector3d(0, 0, 1)};
  // Through the middle, parallel to the x = 0 face.
  EXPECT_TRUE(cutting::crosses(t, {Eigen::Vector3d(0.2, -1, -1), Eigen::Vector3d(0.2, 3, -1), Eigen::Vector3d(0.2, -1, 3)}));
  // Far away, and in the plane of a face (touching only).
  EXPECT_FALSE(cutting::crosses(t, {Eigen::Vector3d(2, 2, 2), Eigen::Vector3d(3, 2, 2), Eigen::Vector3d(2, 3, 2)}));
  EXPECT_FALSE(cutting::crosses(t, {Eigen::Vector3d(0, -1, -1), Eigen::Vector3d(0, 3, -1), Eigen::Vector3d(0, -1, 3)}));
  // A small triangle wholly inside.
  EXPECT_TRUE(cutting::crosses(t, {Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d(0.2, 0.1, 0.1),
                                   Eigen::Vector3d(0.1, 0.2, 0.1)}));
  // Bad sweeps are named.
  cutting::BladeSweep s = across_top(0.01);
  EXPECT_EQ(cutting::sweep_problem(s), "");
  cutting::BladeSweep zero_length = s;
  zero_length.b0 = zero_length.a0;
  zero_length.b1 = zero_length.a1;
  EXPECT_NE(cutting::sweep_problem(zero_length).find("length"), std::string::npos);
  cutting::BladeSweep still = s;
  still.a1 = still.a0;
  still.b1 = still.b0;
  EXPECT_NE(cutting::sweep_problem(still).find("moves"), std::string::npos);
  cutting::BladeSweep nan = s;
  nan.a0.x() = std::nan("");
  EXPECT_NE(cutting::sweep_problem(nan).find("finite"), std::string::npos);
}

// The local update (slots emptied, linear blocks subtracted, ANP volumes re-weighted) gives the
// forces of an element set built from scratch on the mesh without those elements, to round-off,
// for every kind; the mass removed is exactly ρ Σ ⁰V of the removed elements.
// The grid's local search finds exactly the elements the full scan finds, for sweeps of every
// size and place (inside, across, beside, outside the mesh) on a deformed mesh: the widening
// by the largest displacement must not miss an element that moved into the sweep.
TEST(Blade, GridSearchEqualsTheFullScanOnADeformedMesh) {
  const auto m = cuboid(6, 5, 4, 0.06, 0.05, 0.04);
  const cutting::ElementGrid grid(m);
  EXPECT_GT(grid.num_cells(), 1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> shift(-4e-3, 4e-3), place(-0.02, 0.08), unit(-1.0, 1.0);
  std::vector<double> u(3 * m.num_nodes());
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = shift(rng);
  u[3 * 17 + 2] = 0.03;  // one node moved far (3 cm up): its elements reach well outside their boxes
  std::vector<int> scratch;
  int nonempty = 0;
  for (int trial = 0; trial < 300; ++trial) {
    cutting::BladeSweep s;
    s.a0 = Eigen::Vector3d(place(rng), place(rng), place(rng));
    const double len = trial < 150 ? 0.01 : 0.06;
    s.b0 = s.a0 + len * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    const Eigen::Vector3d move = len * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    s.a1 = s.a0 + move;
    s.b1 = s.b0 + move;
    if (!cutting::sweep_problem(s).empty()) continue;
    const double* disp = trial % 3 == 0 ? nullptr : u.data();
    const auto skip = [](int e) { return e % 7 == 3; };
    const auto scanned = cutting::elements_crossed(m, disp, s, skip);
    EXPECT_EQ(cutting::elements_crossed(m, disp, s, grid, scratch, skip), scanned) << "trial " << trial;
    nonempty += !scanned.empty();
  }
  EXPECT_GT(nonempty, 50);  // the comparison is not only between empty lists
}

TEST(Cutting, LocalUpdateEqualsAFullSetUpOnTheCutMesh) {
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::decoupled);
  const auto kinds = mixed_kinds(m.num_tets());
  std::vector<int> removed = cutting::elements_crossed(m, nullptr, across_top(0.015));
  ASSERT_GT(removed.size(), 10u);
  fem::ElementSet cut(m, kinds, mat, 32);
  EXPECT_EQ(cut.remove_elements(m, removed), removed);
  EXPECT_TRUE(cut.remove_elements(m, removed).empty());  // removing twice removes nothing more
  const auto m2 = without(m, removed);
  fem::ElementSet fresh(m2, kinds_without(kinds, removed), mat, 32);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-1e-3, 1e-3);
  std::vector<double> u(3 * m.num_nodes());
  for (double& x : u) x = d(rng);
  const auto fa = test_scenes::gathered_forces(cut, u);
  const auto fb = test_scenes::gathered_forces(fresh, u);
  EXPECT_LT(test_scenes::max_abs_diff(fa, fb), 1e-12 * test_scenes::max_abs(fb));

  // Mass: the solver's update against lumped_mass on the cut mesh.
  dynamics::ExplicitOptions opt;
  opt.dt = 1e-4;
  fem::ElementSet set(m, kinds, mat, 32);
  dynamics::ExplicitSolver solver(set, dynamics::lumped_mass(m, kPaper.density), dynamics::Scene{}, opt);
  const dynamics::CutReport r = solver.remove_elements(m, removed);
  double volume = 0;
  for (int e : removed) volume += mesh::signed_volume(m, m.tets[e]);
  EXPECT_NEAR(r.mass, kPaper.density * volume, 1e-13 * kPaper.density * volume);  // round-off of the sums
  EXPECT_EQ(r.elements, removed);
  EXPECT_EQ(r.detached_nodes, 0);
}

// Patch test on what is left: an affine field gives zero internal force at every node that is
// interior to the remaining mesh (not on the outer boundary, not a corner of a removed element).
TEST(Cutting, PatchTestPassesOnTheMeshLeftAfterACut) {
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  const std::vector<int> removed = cutting::elements_crossed(m, nullptr, across_top(0.015));
  std::vector<char> at_cut(m.num_nodes(), 0);
  for (int e : removed)
    for (int a : m.tets[e]) at_cut[a] = 1;
  Eigen::Matrix3d H;
  H << 0.01, 0.002, -0.003, 0.001, -0.004, 0.002, 0.0, 0.003, 0.005;
  const auto u = test_scenes::affine_field(m, Eigen::Matrix3d::Identity() + H);
  const double scale = kPaper.youngs_modulus * 0.01 * 0.01 * 0.01;  // E |H| h² with h = 1 cm
  for (int k = 0; k < fem::kNumElementKinds; ++k) {  // one kind at a time: a uniform stress
    fem::ElementSet set(m, std::vector<ElementKind>(m.num_tets(), static_cast<ElementKind>(k)), mat, 32);
    set.remove_elements(m, removed);
    const auto f = test_scenes::gathered_forces(set, u);
    int checked = 0;
    for (int i : test_scenes::interior_nodes(m)) {
      if (at_cut[i]) continue;
      ++checked;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[3 * i + c], 0.0, 1e-10 * scale) << "kind " << k << ", node " << i;
    }
    EXPECT_GT(checked, 5);
  }
}

// A cut that removes nothing (a sweep beside the mesh, or an empty list) changes nothing, bit
// for bit; a cut through the whole block leaves two pieces, both loose without constraints.
TEST(Cutting, NothingCutChangesNothingAndAThroughCutLeavesTwoPieces) {
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::decoupled);
  const std::vector<ElementKind> kinds(m.num_tets(), ElementKind::tled);
  dynamics::Scene scene;
  scene.constraints = {test_scenes::constraint(m, "bottom", Eigen::Vector3d::Zero()),
                       test_scenes::constraint(m, "top", Eigen::Vector3d(0, 0.002, -0.004))};
  scene.constraints[1].ramp.duration = 0.05;
  dynamics::ExplicitOptions opt;
  opt.dt = 0.9 * dynamics::critical_time_step(m, kPaper).dt;
  opt.energy_interval = 50;
  auto run = [&](bool cut) {
    fem::ElementSet set(m, kinds, mat, 64);
    dynamics::ExplicitSolver s(set, dynamics::lumped_mass(m, kPaper.density), scene, opt);
    s.advance(300);
    if (cut) {
      cutting::BladeSweep beside = across_top(0.01);
      for (auto* p : {&beside.a0, &beside.b0, &beside.a1, &beside.b1}) p->x() += 1.0;
      const auto crossed = cutting::elements_crossed(m, s.displacement(), beside);
      EXPECT_TRUE(crossed.empty());
      const auto r = s.remove_elements(m, crossed);
      EXPECT_TRUE(r.elements.empty());
    }
    s.advance(300);
    return std::vector<double>(s.displacement(), s.displacement() + 3 * m.num_nodes());
  };
  EXPECT_EQ(run(false), run(true));

  cutting::BladeSweep through = across_top(0.0);
  through.a1.z() = through.b1.z() = -0.01;
  const auto removed = cutting::elements_crossed(m, nullptr, through);
  std::vector<char> gone(m.num_tets(), 0);
  for (int e : removed) gone[e] = 1;
  const auto pieces = cutting::find_pieces(m, [&](int e) { return gone[e] != 0; }, [](int) { return false; });
  EXPECT_EQ(pieces.count, 2);
  EXPECT_EQ(pieces.loose.size(), 2u);
  const auto held = m.node_sets.at("x_min");
  const auto anchored = cutting::find_pieces(
      m, [&](int e) { return gone[e] != 0; }, [&](int n) { return std::binary_search(held.begin(), held.end(), n); });
  EXPECT_EQ(anchored.loose.size(), 1u);
}

// After a cut under load the run stays stable and its energy accounted: no growth over 20 000
// steps, the energy the removed elements carried is booked, and the re-estimated step does not
// shrink (each remaining element keeps its own mass share: the element bound behind 000 eq. 34).
TEST(Cutting, RunAfterACutStaysStableAndBooksTheRemovedEnergy) {
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const auto mesh = std::make_shared<const mesh::TetMesh>(m);
  const nlohmann::json j = test_scenes::pressed_block_cut();
  const auto config = hybrid::read_dhd_config(io::JsonReader(j, "config.json"), m);
  hybrid::DhdScene scene(mesh, config, std::vector<ElementKind>(m.num_tets(), ElementKind::tled));
  const double dt0 = scene.dt();
  const auto r = scene.run();
  ASSERT_EQ(scene.cut_events().size(), 1u);
  const auto& ev = scene.cut_events()[0];
  EXPECT_NEAR(ev.time, 0.06, scene.dt());
  EXPECT_GT(ev.report.elements.size(), 0u);
  EXPECT_GT(ev.report.strain_energy, 0.0);
  EXPECT_EQ(ev.pieces, 1);
  EXPECT_EQ(r.step_history.back().dt, dt0);  // no re-estimate shrank it
  double peak = 0;
  for (const auto& s : r.energies) peak = std::max(peak, s.kinetic + s.strain);
  const auto& last = r.energies.back();
  EXPECT_NEAR(last.removed, ev.report.strain_energy + ev.report.kinetic_energy, 1e-15);
  EXPECT_LT(last.kinetic, 1e-6 * peak);  // damped out, not growing
  EXPECT_GT(last.dissipated, 0.0);
  for (double x : r.displacement) ASSERT_TRUE(std::isfinite(x));
}

TEST(Cutting, BadCutsAreInputErrorsNamingThePointer) {
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  auto expect_error = [&](const nlohmann::json& cuts, const std::string& pointer, const std::string& words,
                          const std::string& solver = "explicit") {
    nlohmann::json j = {{"mesh", "m"}, {"solver", {{"kind", solver}}}, {"cuts", cuts}};
    try {
      hybrid::read_dhd_config(io::JsonReader(j, "c.json"), m);
      ADD_FAILURE() << "accepted " << cuts.dump();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(pointer), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  const nlohmann::json edge = {{0.011, -0.01, 0.03}, {0.011, 0.03, 0.03}};
  const nlohmann::json down = {{0.011, -0.01, 0.005}, {0.011, 0.03, 0.005}};
  expect_error({{{"time", 0.1}, {"from", edge}, {"to", edge}}}, "/cuts/0", "moves");
  expect_error({{{"time", 0.1}, {"from", {edge[0], edge[0]}}, {"to", {down[0], down[0]}}}}, "/cuts/0", "length");
  const nlohmann::json far = {{1.011, -0.01, 0.03}, {1.011, 0.03, 0.03}};
  const nlohmann::json far_down = {{1.011, -0.01, 0.005}, {1.011, 0.03, 0.005}};
  expect_error({{{"time", 0.1}, {"from", far}, {"to", far_down}}}, "/cuts/0", "crosses no element");
  expect_error({{{"time", 0.2}, {"from", edge}, {"to", down}}, {{"time", 0.1}, {"from", edge}, {"to", down}}},
               "/cuts/1/time", "ascending");
  expect_error({{{"time", -1}, {"from", edge}, {"to", down}}}, "/cuts/0/time", "non-negative");
  expect_error({{{"time", 0.1}, {"from", {{0, 0}, {1, 1, 1}}}, {"to", down}}}, "/cuts/0/from/0", "point");
  expect_error({{{"time", 0.1}, {"from", edge}, {"to", down}, {"mode", "slice"}}}, "/cuts/0/mode", "separate");
  expect_error({{{"time", 0.1}, {"from", edge}, {"to", down}}}, "/cuts", "explicit", "static");
}
