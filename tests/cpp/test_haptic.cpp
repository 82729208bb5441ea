// The haptic scene (001 §3 in 3-D on the dhd_sim engine): applied forces enter the explicit
// update exactly as nodal loads do; a probe pressed and held settles on the static solution of
// the same spring; sliding over the surface carries the contact across triangles without a
// force jump; a failure far past inversion is reported and the frames go on; recorded inputs are
// read strictly.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/dynamics/static_solver.hpp"
#include "softsim/haptic/haptic_config.hpp"
#include "softsim/haptic/haptic_run.hpp"
#include "softsim/haptic/haptic_scene.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/mesh/surface.hpp"

#include "support/haptic_block.hpp"
#include "support/scenes.hpp"

using namespace softsim;
namespace fs = std::filesystem;

namespace {

using Block = test_scenes::HapticBlock;
using test_scenes::press_down;
using test_scenes::spring_probe;

int node_at(const mesh::TetMesh& m, const Eigen::Vector3d& x) {
  for (int i = 0; i < m.num_nodes(); ++i)
    if ((m.nodes[i] - x).norm() < 1e-12) return i;
  return -1;
}

}  // namespace

TEST(AppliedForces, EnterTheUpdateExactlyAsANodalLoad) {
  // The same force on one node, once as a scene load acting from step 1 (a ramp of half a step)
  // and once applied between steps after step 0: the same displacements, bit for bit.
  Block b;
  const auto mat = fem::Material::make(test_scenes::kPaper, material::NeoHookeanForm::paper);
  const std::vector<fem::ElementKind> kinds(b.mesh->num_tets(), fem::ElementKind::tled);
  const int node = node_at(*b.mesh, {0.05, 0.05, 0.05});
  ASSERT_GE(node, 0);
  const Eigen::Vector3d force(0.01, -0.02, -0.05);
  const double dt = 1e-4;
  dynamics::ExplicitOptions opt;
  opt.dt = dt;
  opt.steps = 200;
  opt.damping_alpha = 5;
  dynamics::Scene with_load = b.config(0).scene;
  dynamics::NodalLoad load;
  load.name = "push";
  load.nodes = {node};
  load.force_per_node = force;
  load.ramp.duration = 0.5 * dt;
  with_load.loads.push_back(load);

  fem::ElementSet set_a(*b.mesh, kinds, mat), set_b(*b.mesh, kinds, mat);
  const auto masses = dynamics::lumped_mass(*b.mesh, 1000.0);
  dynamics::ExplicitSolver a(set_a, masses, with_load, opt);
  dynamics::ExplicitSolver c(set_b, masses, b.config(0).scene, opt);
  a.reset();
  c.reset();
  a.advance(1);
  c.advance(1);
  c.set_applied_forces({{node, force}});
  a.advance(199);
  c.advance(199);
  for (int q = 0; q < 3 * b.mesh->num_nodes(); ++q) ASSERT_EQ(a.displacement()[q], c.displacement()[q]) << q;
  // The work of the applied force is booked: the energy balance closes as with the load.
  EXPECT_NEAR(c.energies().back().external_work, a.energies().back().external_work,
              1e-3 * std::abs(a.energies().back().external_work));
  // An empty set removes the force; the node then moves freely (the state diverges from the load's).
  c.set_applied_forces({});
  a.advance(50);
  c.advance(50);
  EXPECT_NE(a.displacement()[3 * node + 2], c.displacement()[3 * node + 2]);
}

TEST(HapticScene, PressAndHoldSettlesOnTheStaticSpringSolution) {
  // The tip pressed 8 mm straight down over a top node and held: with damping the frames settle
  // where the static solver puts the same spring on that node.
  Block b;
  const haptic::HapticOptions opt = spring_probe(100);
  haptic::HapticScene scene(b.mesh, b.config(40), opt);
  const int node = node_at(*b.mesh, {0.05, 0.05, 0.05});
  const Eigen::Vector3d depth(0, 0, -0.008);
  const haptic::ProbePath path = press_down(b.mesh->nodes[node], 0.008, 0.3);
  const haptic::HapticRecord r = haptic::run_haptic(scene, path, 3000);
  ASSERT_TRUE(scene.events().empty());
  // The contact stayed on the node (the bottom of the dimple).
  EXPECT_NEAR(scene.contact().weights.maxCoeff(), 1.0, 1e-9);

  dynamics::Scene s = b.config(0).scene;
  s.has_probe = true;
  s.probe.node = node;
  s.probe.stiffness = opt.probe_stiffness;
  s.probe.displacement = depth;
  const auto kinds = std::vector<fem::ElementKind>(b.mesh->num_tets(), fem::ElementKind::tled);
  const auto st = dynamics::solve_static(*b.mesh, kinds, b.config(0).material, s, dynamics::StaticOptions());
  // Force on the tool = −(spring force on the tissue).
  const Eigen::Vector3d expected = -st.probe_force;
  EXPECT_LT((r.force.back() - expected).norm(), 1e-4 * expected.norm()) << r.force.back().transpose() << " vs "
                                                                          << expected.transpose();
  EXPECT_GT(expected.z(), 0.1);  // the tool is pushed back up
}

// The tissue laws with more than F in the haptic scene: a fibre-reinforced, relaxing block (the
// fibre law with a Prony series) pressed and held settles where the static solver, which sees
// the relaxed law, puts the same spring.
TEST(HapticScene, AFibreReinforcedRelaxingTissueSettlesOnItsRelaxedStaticSolution) {
  Block b;
  const nlohmann::json material = {{"model", "transversely_isotropic"}, {"mu", 1850.0}, {"eta", 3000.0},
                                   {"K", 5556.0}, {"fibre", {1.0, 0.0, 0.0}}, {"density", 1000.0},
                                   {"prony", {{"g", {0.5}}, {"tau", {0.05}}}}};
  const haptic::HapticOptions opt = spring_probe(100);
  haptic::HapticScene scene(b.mesh, b.config(40, material), opt);
  const int node = node_at(*b.mesh, {0.05, 0.05, 0.05});
  const haptic::HapticRecord r = haptic::run_haptic(scene, press_down(b.mesh->nodes[node], 0.008, 0.3), 3000);
  ASSERT_TRUE(scene.events().empty());
  dynamics::Scene s = b.config(0, material).scene;
  s.has_probe = true;
  s.probe.node = node;
  s.probe.stiffness = opt.probe_stiffness;
  s.probe.displacement = Eigen::Vector3d(0, 0, -0.008);
  const auto kinds = std::vector<fem::ElementKind>(b.mesh->num_tets(), fem::ElementKind::tled);
  const auto relaxed = dynamics::solve_static(*b.mesh, kinds, b.config(0, material).material, s, dynamics::StaticOptions());
  EXPECT_LT((r.force.back() + relaxed.probe_force).norm(), 1e-3 * relaxed.probe_force.norm())
      << r.force.back().transpose() << " vs " << (-relaxed.probe_force).transpose();
}

// Contact "tool": a rigid plate (a plane tool over the top face) at the tip, pressed 3 mm and
// held: with damping the force on the device settles on the static solution of the top face's z
// displacement prescribed to the same depth (x and y free: the contact is frictionless), i.e.
// minus that constraint's reaction on the body.
TEST(HapticScene, ARigidToolAtTheTipSettlesOnTheStaticSolution) {
  Block b;
  const double depth = 0.003;
  nlohmann::json j = {{"mesh", "unused"},
                      {"material", {{"E", 5000.0}, {"nu", 0.35}, {"density", 1000.0}}},
                      {"damping", {{"alpha", 40.0}}},
                      {"boundary",
                       {{"fixed", {{{"set", "bottom"}}}},
                        {"tools", {{{"shape", "plane"}, {"normal", {0, 0, -1}}, {"position", {0, 0, 1}}, {"nodes", "top"}}}}}},
                      {"solver", {{"kind", "explicit"}}}};
  const auto model = hybrid::read_dhd_config(io::JsonReader(j, "block.json"), *b.mesh);
  haptic::HapticOptions opt;
  opt.contact = haptic::ContactMode::tool;
  haptic::HapticScene scene(b.mesh, model, opt);
  const haptic::HapticRecord r = haptic::run_haptic(scene, press_down({0.05, 0.05, 0.05}, depth, 0.3), 3000);
  ASSERT_TRUE(scene.events().empty());
  EXPECT_TRUE(scene.in_contact());

  dynamics::Scene s = b.config(0).scene;
  dynamics::DisplacementConstraint top;
  top.name = "top";
  top.nodes = b.mesh->node_sets.at("top");
  top.components = {false, false, true};
  top.displacement = Eigen::Vector3d(0, 0, -depth);
  s.constraints.push_back(top);
  const auto kinds = std::vector<fem::ElementKind>(b.mesh->num_tets(), fem::ElementKind::tled);
  const auto st = dynamics::solve_static(*b.mesh, kinds, b.config(0).material, s, dynamics::StaticOptions());
  const Eigen::Vector3d expected = -st.reactions.back();  // on the tool = −(on the body)
  EXPECT_GT(expected.z(), 0.1);                          // the tissue pushes the plate back up
  EXPECT_LT((r.force.back() - expected).norm(), 1e-4 * expected.norm()) << r.force.back().transpose() << " vs "
                                                                          << expected.transpose();
}

TEST(HapticScene, SlidingCrossesTrianglesWithoutAForceJump) {
  Block b;
  haptic::HapticScene scene(b.mesh, b.config(40), spring_probe(100));
  haptic::ProbePath path = press_down({0.031, 0.052, 0.05}, 0.005, 0.2);
  path.kind = haptic::ProbePath::Kind::slide;
  path.slide_direction = Eigen::Vector3d::UnitX();
  path.slide_speed = 0.02;  // 2 cm/s: 3 cm (2.4 cells) in 1.5 s
  std::vector<int> triangles;
  haptic::HapticRecord r;
  double largest_jump = 0, largest_force = 0;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  for (long k = 0; k < 1700; ++k) {
    const Eigen::Vector3d f = scene.frame(path.at(k * 1e-3));
    if (triangles.empty() || triangles.back() != scene.contact().triangle) triangles.push_back(scene.contact().triangle);
    if (k > 400) largest_jump = std::max(largest_jump, (f - previous).norm());
    largest_force = std::max(largest_force, f.norm());
    previous = f;
  }
  ASSERT_TRUE(scene.events().empty());
  EXPECT_GE(triangles.size(), 5u);  // the contact crossed several edges
  // Held at the nearest node instead, the force would jump by about k × (half a cell) = 0.6 N.
  EXPECT_LT(largest_jump, 0.01 * largest_force) << largest_jump << " N of " << largest_force << " N";
  // It followed the tip: the contact point sits near the tip's x.
  EXPECT_NEAR(scene.contact().position.x(), path.at(1.699).x(), 0.003);
}

// Attached (a probe glued to the point it first touches): the same slide never leaves the first
// contact triangle, the material point stays at its weights, and the spring stretches along
// the slide, so the tangential force grows, where the frictionless grasp slid with the tip.
TEST(HapticScene, AnAttachedContactHoldsItsMaterialPointWhileTheTipSlides) {
  Block b;
  auto options = spring_probe(100);
  options.contact = haptic::ContactMode::attach;
  haptic::HapticScene scene(b.mesh, b.config(40), options);
  haptic::ProbePath path = press_down({0.031, 0.052, 0.05}, 0.005, 0.2);
  path.kind = haptic::ProbePath::Kind::slide;
  path.slide_direction = Eigen::Vector3d::UnitX();
  path.slide_speed = 0.02;
  scene.frame(path.at(0));
  const int triangle = scene.contact().triangle;
  const auto weights = scene.contact().weights;
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  for (long k = 1; k < 700; ++k) {
    f = scene.frame(path.at(k * 1e-3));
    ASSERT_EQ(scene.contact().triangle, triangle) << "frame " << k;
    ASSERT_EQ(scene.contact().weights, weights) << "frame " << k;
  }
  ASSERT_TRUE(scene.events().empty());
  // The tip is 1 cm ahead in x (0.5 s at 2 cm/s) and the tissue holds it back: the force on the
  // tool points along -x, a tangential force the frictionless grasp cannot transmit.
  EXPECT_LT(f.x(), -0.1 * f.norm()) << f.transpose();
  EXPECT_GT(path.at(0.699).x() - scene.contact().position.x(), 0.002);
}

TEST(HapticScene, AFailurePastInversionIsReportedAndTheFramesGoOn) {
  Block b;
  haptic::HapticScene scene(b.mesh, b.config(10), spring_probe(1e4));
  const haptic::ProbePath path = press_down({0.05, 0.05, 0.05}, 0.2, 0.2);  // 4x the block's height
  const haptic::HapticRecord r = haptic::run_haptic(scene, path, 400);
  EXPECT_EQ(r.frames, 400);
  ASSERT_FALSE(scene.events().empty());
  EXPECT_NE(scene.events().front().message.find("inverted"), std::string::npos) << scene.events().front().message;
  for (const auto& f : r.force) EXPECT_TRUE(f.allFinite());
}

// A blade on the tool (019): dragged across the block, it cuts the elements it passes; the
// contact surface, updated locally at each cut, is the outward boundary of the mesh left (the
// same oriented triangles as extracted from scratch); the frames go on without events.
TEST(HapticScene, ABladeOnTheToolCutsAndTheSurfaceFollows) {
  Block b;
  haptic::HapticScene scene(b.mesh, b.config(40), test_scenes::vertical_blade(hybrid::CutMode::remove));
  const int before = scene.surface().num_triangles();
  test_scenes::draw_blade_across(scene);
  ASSERT_TRUE(scene.events().empty());
  const auto& cuts = scene.model().cut_events();
  ASSERT_FALSE(cuts.empty());
  std::vector<int> removed;
  for (int e = 0; e < b.mesh->num_tets(); ++e)
    if (scene.model().removed(e)) removed.push_back(e);
  EXPECT_GT(removed.size(), 10u);
  mesh::TetMesh left = *b.mesh;
  left.tets.clear();
  for (int e = 0; e < b.mesh->num_tets(); ++e)
    if (!scene.model().removed(e)) left.tets.push_back(b.mesh->tets[e]);
  const auto fresh = test_scenes::oriented_triangle_set(mesh::extract_boundary(left, "cut block"));
  EXPECT_EQ(test_scenes::surface_triangle_set(scene.surface()), fresh);
  EXPECT_GT(static_cast<int>(fresh.size()), before);
}

// The same blade separating instead (019): nothing is removed, the mesh gains node copies, and
// the followed surface is the outward boundary of the cut mesh (its opened faces included), the
// same oriented triangles as extracted from scratch; the frames go on without events.
TEST(HapticScene, ASeparatingBladeOpensTheMeshAndTheSurfaceFollows) {
  Block b;
  const haptic::HapticOptions opt = test_scenes::vertical_blade(hybrid::CutMode::separate);
  hybrid::DhdConfig config = b.config(40);
  EXPECT_THROW(haptic::HapticScene(b.mesh, config, opt), InputError);  // the model must allow it
  config.separates = true;
  haptic::HapticScene scene(b.mesh, config, opt);
  const int before = scene.surface().num_triangles();
  test_scenes::draw_blade_across(scene);
  ASSERT_TRUE(scene.events().empty());
  ASSERT_FALSE(scene.model().cut_events().empty());
  const mesh::TetMesh& cut = scene.model().mesh();
  EXPECT_GT(cut.num_nodes(), b.mesh->num_nodes());
  for (int e = 0; e < cut.num_tets(); ++e) EXPECT_FALSE(scene.model().removed(e));
  const auto fresh = test_scenes::oriented_triangle_set(mesh::extract_boundary(cut, "cut block"));
  EXPECT_EQ(test_scenes::surface_triangle_set(scene.surface()), fresh);
  EXPECT_GT(static_cast<int>(fresh.size()), before);
  for (int i = 0; i < 3 * cut.num_nodes(); ++i) ASSERT_TRUE(std::isfinite(scene.displacement()[i]));
}

TEST(RecordedPath, ReadStrictlyAndInterpolated) {
  const fs::path dir = fs::temp_directory_path() / "softsim_test_haptic";
  fs::create_directories(dir);
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  };
  const auto good = haptic::read_recorded_path(write("good.txt", "# t x y z\n0 0 0 0\n\n0.5 1 2 3 # mid\n1 1 2 5\n"));
  EXPECT_EQ(good.at(0.25), Eigen::Vector3d(0.5, 1, 1.5));
  EXPECT_EQ(good.at(2.0), Eigen::Vector3d(1, 2, 5));
  auto expect_error = [&](const std::string& name, const std::string& text, const std::string& what) {
    const std::string p = write(name, text);
    try {
      haptic::read_recorded_path(p);
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(p + ":" + what), std::string::npos) << e.what();
    }
  };
  expect_error("nan.txt", "0 0 0 0\n0.1 nan 0 0\n", "2: expected a finite number");
  expect_error("back.txt", "0 0 0 0\n0.1 0 0 0\n0.1 0 0 1\n", "3: expected a time after");
  expect_error("short.txt", "0 0 0\n", "1: expected 4 numbers");
  expect_error("word.txt", "0 0 0 x\n", "1: expected a number");
  fs::remove_all(dir);
}

// A probe spring far stiffer than the tissue under it (20 kN/m against a node of about a gram at
// 1 kHz): held over the frame (the explicit coupling at the frame step) the pressed block
// diverges (caught as events, the frames go on); integrated at every substep (the virtual
// coupling, the substep shortened for the spring) it settles where the static solver puts the
// same spring, for the whole model and the linked regions; no frame of either sends a force that
// is not finite or beyond the spring's stretch over the organ's size.
TEST(HapticScene, AStiffProbeSpringCoupledAtTheSubstepsSettlesOnTheStaticSolution) {
  Block b;
  const double k = 20000;
  const int node = node_at(*b.mesh, {0.05, 0.05, 0.05});
  const haptic::ProbePath path = press_down(b.mesh->nodes[node], 0.004, 0.1);
  dynamics::Scene s = b.config(0).scene;
  s.has_probe = true;
  s.probe.node = node;
  s.probe.stiffness = k;
  s.probe.displacement = Eigen::Vector3d(0, 0, -0.004);
  const auto kinds = std::vector<fem::ElementKind>(b.mesh->num_tets(), fem::ElementKind::tled);
  const Eigen::Vector3d expected = -dynamics::solve_static(*b.mesh, kinds, b.config(0).material, s, dynamics::StaticOptions()).probe_force;
  const double bound = k * 0.15;  // k × the block's diagonal: the runaway guard's limit  // k × the block's diagonal
  auto settled = [&](haptic::HapticOptions opt, bool& sane) {
    haptic::HapticScene scene(b.mesh, b.config(40), opt);
    const haptic::HapticRecord r = haptic::run_haptic(scene, path, 1500);
    sane = true;
    for (const auto& f : r.force) sane = sane && f.allFinite() && f.norm() <= bound;
    return scene.events().empty() && (r.force.back() - expected).norm() < 1e-3 * expected.norm();
  };
  haptic::HapticOptions held = spring_probe(k);
  haptic::HapticOptions coupled = held;
  coupled.spring_coupling = haptic::SpringCoupling::substep;
  haptic::HapticOptions coupled_regions = spring_probe(k, 0.03);
  coupled_regions.spring_coupling = haptic::SpringCoupling::substep;
  bool sane = false;
  EXPECT_FALSE(settled(held, sane));
  EXPECT_TRUE(sane);
  EXPECT_TRUE(settled(coupled, sane));
  EXPECT_TRUE(sane);
  haptic::HapticScene regions(b.mesh, b.config(40), coupled_regions);
  const haptic::HapticRecord r = haptic::run_haptic(regions, path, 1500);
  EXPECT_TRUE(regions.events().empty());
  // The regions' far field is linear (condensed, small strain): the settled force within 2 %.
  EXPECT_LT((r.force.back() - expected).norm(), 0.02 * expected.norm());
}
