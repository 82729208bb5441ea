// Linked asynchronous regions in 3-D (001 §5 on the dhd_sim engine): a primary region covering
// the mesh is the whole model, bit for bit; the far field's Guyan mass is its whole mass when only
// the interface holds it, and vanishes with it; with a linear model, the condensed coupling settles
// exactly on the whole model's static answer and the exchange of 001 eq. 7 converges to it;
// a sliding contact moves the region without a force jump; skipping a secondary update that
// nothing moved is counted; bad region input is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/haptic/haptic_config.hpp"
#include "softsim/haptic/haptic_run.hpp"
#include "softsim/haptic/haptic_scene.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/regions/primary_region.hpp"
#include "softsim/regions/secondary_region.hpp"

#include "support/haptic_block.hpp"
#include "support/scenes.hpp"

using namespace softsim;

namespace {

using Block = test_scenes::HapticBlock;
using test_scenes::press_down;

haptic::HapticOptions with_regions(double radius, regions::Coupling coupling, int every, bool interpolate = true) {
  haptic::HapticOptions opt;
  opt.probe_stiffness = 100;
  opt.use_regions = true;
  opt.regions.radius = radius;
  opt.regions.coupling = coupling;
  opt.regions.secondary_every = every;
  opt.regions.interpolate = interpolate;
  return opt;
}

haptic::HapticOptions whole_model() {
  haptic::HapticOptions opt;
  opt.probe_stiffness = 100;
  return opt;
}

const Eigen::Vector3d kTop(0.05, 0.05, 0.05);

}  // namespace

TEST(PrimaryRegion, SplitsNodesIntoInteriorInterfaceAndSecondary) {
  Block b;
  const auto& m = *b.mesh;
  int centre = 0;
  for (int i = 0; i < m.num_nodes(); ++i)
    if ((m.nodes[i] - kTop).norm() < 1e-12) centre = i;
  const regions::PrimaryRegion r = regions::select_primary_region(m, centre, 0.025);
  ASSERT_FALSE(r.interface.empty());
  std::vector<int> primary_touch(m.num_nodes(), 0), secondary_touch(m.num_nodes(), 0);
  std::vector<char> is_neighbour(m.num_nodes(), 0);
  for (const auto& t : m.tets)
    if (std::find(t.begin(), t.end(), centre) != t.end())
      for (int n : t) is_neighbour[n] = 1;
  std::vector<char> primary(m.num_tets(), 0);
  for (int e : r.elements) primary[e] = 1;
  for (int e = 0; e < m.num_tets(); ++e) {
    bool near = false;
    for (int n : m.tets[e]) near = near || (m.nodes[n] - kTop).norm() <= 0.025 || is_neighbour[n];
    EXPECT_EQ(near, primary[e] != 0) << "element " << e;
    for (int n : m.tets[e]) (primary[e] ? primary_touch : secondary_touch)[n] = 1;
  }
  for (int i = 0; i < m.num_nodes(); ++i) {
    EXPECT_EQ(r.interior[i] != 0, primary_touch[i] && !secondary_touch[i]);
    EXPECT_EQ(r.local[i] >= 0, primary_touch[i] != 0);
  }
  for (int i : r.interface) EXPECT_TRUE(primary_touch[i] && secondary_touch[i]);
  // However small the radius, the centre's neighbours are interior (a contact triangle on the
  // centre is solved every frame).
  const regions::PrimaryRegion tiny = regions::select_primary_region(m, centre, 1e-6);
  for (const auto& t : m.tets)
    if (std::find(t.begin(), t.end(), centre) != t.end())
      for (int n : t) EXPECT_TRUE(tiny.interior[n]) << n;
  // The sub-mesh is the primary elements on renumbered nodes, same geometry.
  ASSERT_EQ(r.submesh.num_tets(), static_cast<int>(r.elements.size()));
  for (std::size_t k = 0; k < r.elements.size(); ++k)
    for (int c = 0; c < 4; ++c)
      EXPECT_EQ(r.nodes[r.submesh.tets[k][c]], m.tets[r.elements[k]][c]);
  EXPECT_THROW(regions::select_primary_region(m, centre, 0.0), InputError);
  EXPECT_THROW(regions::select_primary_region(m, -1, 0.02), InputError);
}

TEST(Regions, APrimaryRegionCoveringTheMeshIsTheWholeModelBitForBit) {
  Block b;
  const haptic::ProbePath path = press_down(kTop, 0.008, 0.2);
  haptic::HapticScene whole(b.mesh, b.config(15), whole_model());
  haptic::HapticScene all(b.mesh, b.config(15), with_regions(1.0, regions::Coupling::condensed, 10));
  auto guyan = with_regions(1.0, regions::Coupling::condensed, 10);
  guyan.regions.far_field_mass = true;  // no far field: no mass to add
  haptic::HapticScene all_guyan(b.mesh, b.config(15), guyan);
  const auto rw = haptic::run_haptic(whole, path, 400);
  const auto ra = haptic::run_haptic(all, path, 400);
  const auto rg = haptic::run_haptic(all_guyan, path, 400);
  ASSERT_NE(all.regions(), nullptr);
  EXPECT_TRUE(all.regions()->active()->region().interface.empty());
  for (std::size_t k = 0; k < rw.force.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(rw.force[k][c], ra.force[k][c]) << "frame " << k;
      ASSERT_EQ(rw.force[k][c], rg.force[k][c]) << "frame " << k;
    }
}

// With a linear model the primary region is linear too, and the condensed secondary is its
// exact quasi-static complement: once the damped press settles, the force equals the whole
// model's. The exchange of 001 eq. 7 is a block Gauss-Seidel sweep per update, whose fixed point
// is the same equilibrium.
TEST(Regions, OnALinearModelBothCouplingsSettleOnTheWholeModelsForce) {
  Block b;
  const haptic::ProbePath path = press_down(kTop, 0.006, 0.2);
  const long frames = 4000;
  haptic::HapticScene whole(b.mesh, b.config(40, "linear"), whole_model());
  const Eigen::Vector3d expected = haptic::run_haptic(whole, path, frames).force.back();
  ASSERT_GT(expected.z(), 0.1);
  haptic::HapticScene condensed(b.mesh, b.config(40, "linear"), with_regions(0.03, regions::Coupling::condensed, 10));
  const auto rc = haptic::run_haptic(condensed, path, frames);
  ASSERT_TRUE(condensed.events().empty());
  ASSERT_FALSE(condensed.regions()->active()->region().interface.empty());
  EXPECT_LT((rc.force.back() - expected).norm(), 1e-6 * expected.norm())
      << rc.force.back().transpose() << " vs " << expected.transpose();
  haptic::HapticScene exchange(b.mesh, b.config(40, "linear"),
                               with_regions(0.03, regions::Coupling::exchange, 5, false));
  const auto re = haptic::run_haptic(exchange, path, frames);
  ASSERT_TRUE(exchange.events().empty());
  EXPECT_LT((re.force.back() - expected).norm(), 1e-4 * expected.norm())
      << re.force.back().transpose() << " vs " << expected.transpose();
  // An implicit-dynamic secondary (its own inertia) has the same equilibrium.
  auto dynamic = with_regions(0.03, regions::Coupling::exchange, 5, false);
  dynamic.regions.secondary_dynamic = true;
  haptic::HapticScene implicit(b.mesh, b.config(40, "linear"), dynamic);
  const auto ri = haptic::run_haptic(implicit, path, frames);
  ASSERT_TRUE(implicit.events().empty());
  EXPECT_LT((ri.force.back() - expected).norm(), 1e-4 * expected.norm())
      << ri.force.back().transpose() << " vs " << expected.transpose();
  // While the press moves, the condensed coupling follows the whole model far more closely.
  haptic::HapticScene moving_whole(b.mesh, b.config(40, "linear"), whole_model());
  const auto rw = haptic::run_haptic(moving_whole, path, 300);
  double err_c = 0, err_e = 0;
  for (int k = 0; k < 300; ++k) {
    err_c = std::max(err_c, (rc.force[k] - rw.force[k]).norm());
    err_e = std::max(err_e, (re.force[k] - rw.force[k]).norm());
  }
  EXPECT_LT(err_c, err_e);
}

// Guyan: a far field held by nothing but the interface moves rigidly with it (Ψ e = e), so the
// mass it lays on the interface nodes is its whole mass, to round-off.
TEST(CondensedSecondary, AFarFieldHeldOnlyByTheInterfaceLaysItsWholeMassOnIt) {
  Block b;
  const auto& m = *b.mesh;
  int centre = 0;
  for (int i = 0; i < m.num_nodes(); ++i)
    if ((m.nodes[i] - kTop).norm() < 1e-12) centre = i;
  const regions::PrimaryRegion r = regions::select_primary_region(m, centre, 0.03);
  const fem::Material material = b.config(10).material;
  const std::vector<double> masses = dynamics::lumped_mass(m, material.elastic.density);
  const regions::LinearModel linear(m, material, std::vector<char>(3 * m.num_nodes(), 0),
                                    Eigen::VectorXd::Zero(3 * m.num_nodes()), masses);
  regions::CondensedSecondary far(linear, r);
  const std::vector<double> extra = far.interface_masses();
  ASSERT_EQ(extra.size(), r.interface.size());
  double far_mass = 0, laid = 0;
  for (int i = 0; i < m.num_nodes(); ++i)
    if (r.local[i] < 0) far_mass += masses[i];
  for (double x : extra) {
    EXPECT_GE(x, 0.0);
    laid += x;
  }
  ASSERT_GT(far_mass, 0.1);
  EXPECT_NEAR(laid, far_mass, 1e-9 * far_mass);
  // Linear in the far field's masses: as they go to zero, the static condensation is left.
  std::vector<double> light = masses;
  for (double& x : light) x *= 1e-6;
  const regions::LinearModel light_linear(m, material, std::vector<char>(3 * m.num_nodes(), 0),
                                          Eigen::VectorXd::Zero(3 * m.num_nodes()), light);
  const std::vector<double> light_extra = regions::CondensedSecondary(light_linear, r).interface_masses();
  for (std::size_t a = 0; a < extra.size(); ++a) EXPECT_NEAR(light_extra[a], 1e-6 * extra[a], 1e-12 * extra[a] + 1e-300);
}

// Mass changes no equilibrium: with the far field's inertia on the interface the condensed
// coupling still settles on the whole linear model's force; the single-precision interface
// product follows the double one to the float's rounding.
TEST(Regions, TheFarFieldsInertiaAndSinglePrecisionKeepTheStaticAnswer) {
  Block b;
  const haptic::ProbePath path = press_down(kTop, 0.006, 0.2);
  const long frames = 4000;
  haptic::HapticScene whole(b.mesh, b.config(40, "linear"), whole_model());
  const Eigen::Vector3d expected = haptic::run_haptic(whole, path, frames).force.back();
  auto guyan = with_regions(0.03, regions::Coupling::condensed, 10);
  guyan.regions.far_field_mass = true;
  haptic::HapticScene inertial(b.mesh, b.config(40, "linear"), guyan);
  const auto rg = haptic::run_haptic(inertial, path, frames);
  ASSERT_TRUE(inertial.events().empty());
  EXPECT_LT((rg.force.back() - expected).norm(), 1e-6 * expected.norm())
      << rg.force.back().transpose() << " vs " << expected.transpose();
  haptic::HapticScene plain(b.mesh, b.config(40, "linear"), with_regions(0.03, regions::Coupling::condensed, 10));
  auto single = with_regions(0.03, regions::Coupling::condensed, 10);
  single.regions.single_precision = true;
  haptic::HapticScene reduced(b.mesh, b.config(40, "linear"), single);
  const auto rp = haptic::run_haptic(plain, path, 600);
  const auto rs = haptic::run_haptic(reduced, path, 600);
  double largest = 0, peak = 0;
  for (int k = 0; k < 600; ++k) {
    largest = std::max(largest, (rs.force[k] - rp.force[k]).norm());
    peak = std::max(peak, rp.force[k].norm());
  }
  EXPECT_LT(largest, 1e-5 * peak) << largest << " N of " << peak << " N";
  EXPECT_GT(largest, 0.0);  // it did run in single precision
}

TEST(Regions, ASlidingContactMovesTheRegionWithoutAForceJump) {
  Block b;
  haptic::HapticScene scene(b.mesh, b.config(40), with_regions(0.025, regions::Coupling::condensed, 10));
  haptic::ProbePath path = press_down({0.031, 0.052, 0.05}, 0.005, 0.2);
  path.kind = haptic::ProbePath::Kind::slide;
  path.slide_direction = Eigen::Vector3d::UnitX();
  path.slide_speed = 0.02;
  const auto r = haptic::run_haptic(scene, path, 1700);
  ASSERT_TRUE(scene.events().empty());
  EXPECT_GE(scene.regions()->builds().builds, 2);  // built at the start, moved as the contact slid
  double largest_jump = 0, largest_force = 0;
  for (std::size_t k = 401; k < r.force.size(); ++k) {
    largest_jump = std::max(largest_jump, (r.force[k] - r.force[k - 1]).norm());
    largest_force = std::max(largest_force, r.force[k].norm());
  }
  EXPECT_LT(largest_jump, 0.01 * largest_force) << largest_jump << " N of " << largest_force << " N";
  EXPECT_NEAR(scene.contact().position.x(), path.at(1.699).x(), 0.003);
}

TEST(Regions, SecondaryUpdatesThatNothingMovedAreSkippedAndCounted) {
  Block b;
  const haptic::ProbePath path = press_down(kTop, 0.006, 0.2);
  auto opt = with_regions(0.03, regions::Coupling::exchange, 5, false);
  haptic::HapticScene every(b.mesh, b.config(40), opt);
  haptic::run_haptic(every, path, 2000);
  EXPECT_EQ(every.regions()->totals().secondary_updates, 400);
  EXPECT_EQ(every.regions()->totals().secondary_skipped, 0);
  opt.regions.skip_below = 1e-6;
  haptic::HapticScene skipping(b.mesh, b.config(40), opt);
  const auto r = haptic::run_haptic(skipping, path, 2000);
  const auto st = skipping.regions()->totals();
  EXPECT_EQ(st.secondary_updates + st.secondary_skipped, 400);
  EXPECT_GT(st.secondary_skipped, 100);  // the held press comes to rest
  EXPECT_GT(st.secondary_updates, 40);   // while it moved, every update was done
  EXPECT_TRUE(r.force.back().allFinite());
}

TEST(Regions, BadRegionInputIsRefused) {
  Block b;
  // A rigid tool the probe does not drive (the regions follow the probe's tool only).
  nlohmann::json with_tool = {{"mesh", "unused"},
                              {"material", Block::paper_material()},
                              {"boundary", {{"fixed", {{{"set", "bottom"}}}},
                                            {"tools", {{{"shape", "sphere"}, {"radius", 0.01}, {"position", {0.05, 0.05, 0.07}}, {"nodes", "top"}}}}}},
                              {"solver", {{"kind", "explicit"}}}};
  const auto tool_model = hybrid::read_dhd_config(io::JsonReader(with_tool, "block.json"), *b.mesh);
  EXPECT_THROW(haptic::HapticScene(b.mesh, tool_model, with_regions(0.02, regions::Coupling::condensed, 10)), InputError);
  auto negative_margin = with_regions(0.02, regions::Coupling::condensed, 10);
  negative_margin.contact = haptic::ContactMode::tool;
  negative_margin.tool_margin = std::nan("");
  EXPECT_THROW(haptic::HapticScene(b.mesh, tool_model, negative_margin), InputError);
  EXPECT_THROW(haptic::HapticScene(b.mesh, b.config(10), with_regions(0, regions::Coupling::condensed, 10)), InputError);

  const nlohmann::json model = {{"mesh", "unused"},
                                {"material", {{"E", 5000.0}, {"nu", 0.35}, {"density", 1000.0}}},
                                {"boundary", {{"fixed", {{{"set", "bottom"}}}}}}};
  const nlohmann::json input = {{"kind", "press"}, {"start", {0.05, 0.05, 0.06}}, {"direction", {0, 0, -1}},
                                {"depth", 0.005}, {"ramp_time", 0.2}};
  for (const nlohmann::json& regions : {nlohmann::json{{"radius", -1}},
                                        nlohmann::json{{"radius", 0.02}, {"coupling", "iterate"}},
                                        nlohmann::json{{"radius", 0.02}, {"secondary_every", 0}},
                                        nlohmann::json{{"radius", 0.02}, {"skip_below", -1}},
                                        nlohmann::json{{"radius", 0.02}, {"coupling", "exchange"}, {"secondary", "guyan"}},
                                        nlohmann::json{{"radius", 0.02}, {"secondary", "implicit"}},
                                        nlohmann::json{{"radius", 0.02}, {"coupling", "exchange"}, {"precision", "single"}},
                                        nlohmann::json{{"radius", 0.02}, {"precision", "half"}},
                                        nlohmann::json{{"radius", 0.02}, {"unknown", 1}}}) {
    const nlohmann::json cfg = {{"model", model}, {"probe", {{"stiffness", 100}}}, {"input", input}, {"regions", regions}};
    try {
      haptic::read_haptic_config(io::JsonReader(cfg, "scene.json"), *b.mesh);
      ADD_FAILURE() << regions.dump();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("/regions"), std::string::npos) << e.what();
    }
  }
}

TEST(Regions, TheAttachedContactAndTheFarFieldOptionsAreRead) {
  Block b;
  const nlohmann::json model = {{"mesh", "unused"},
                                {"material", {{"E", 5000.0}, {"nu", 0.35}, {"density", 1000.0}}},
                                {"boundary", {{"fixed", {{{"set", "bottom"}}}}}}};
  const nlohmann::json input = {{"kind", "press"}, {"start", {0.05, 0.05, 0.06}}, {"direction", {0, 0, -1}},
                                {"depth", 0.005}, {"ramp_time", 0.2}};
  const nlohmann::json cfg = {{"model", model},
                              {"probe", {{"stiffness", 20}, {"contact", "attach"}}},
                              {"input", input},
                              {"regions", {{"radius", 0.02}, {"secondary", "guyan"}, {"precision", "single"}}}};
  const haptic::HapticConfig c = haptic::read_haptic_config(io::JsonReader(cfg, "scene.json"), *b.mesh);
  EXPECT_EQ(c.options.contact, haptic::ContactMode::attach);
  EXPECT_TRUE(c.options.regions.far_field_mass);
  EXPECT_TRUE(c.options.regions.single_precision);
  EXPECT_FALSE(c.options.regions.secondary_dynamic);
}

// 001 Fig. 5: the primary radius follows the contact's displacement (a gradient, a minimum and a
// maximum), one region per size level, handed over without a force jump.
TEST(Regions, TheAdaptiveRadiusGrowsWithThePressWithoutAForceJump) {
  Block b;
  auto opt = with_regions(0.015, regions::Coupling::condensed, 10);
  opt.regions.adaptive.kind = regions::AdaptiveRadius::Kind::linear;
  opt.regions.adaptive.max_radius = 0.035;
  opt.regions.adaptive.levels = 3;
  opt.regions.adaptive.gradient = 2.5;  // 8 mm of contact displacement: the maximum
  haptic::HapticScene scene(b.mesh, b.config(40), opt);
  const auto r = haptic::run_haptic(scene, press_down(kTop, 0.01, 0.4), 800);
  ASSERT_TRUE(scene.events().empty());
  const auto& levels = scene.regions()->frames_per_level();
  EXPECT_GT(levels[0], 0);
  EXPECT_GT(levels[2], 0);
  EXPECT_EQ(scene.regions()->builds().builds, 3);
  EXPECT_DOUBLE_EQ(scene.regions()->active_radius(), 0.035);
  double largest_jump = 0, largest_force = 0;
  for (std::size_t k = 1; k < r.force.size(); ++k) {
    largest_jump = std::max(largest_jump, (r.force[k] - r.force[k - 1]).norm());
    largest_force = std::max(largest_force, r.force[k].norm());
  }
  // The press itself changes the force by about peak / 400 per frame.
  EXPECT_LT(largest_jump, 0.01 * largest_force) << largest_jump << " N of " << largest_force << " N";
}

// A moved region resumes the central difference from the state it is handed: stepping on from a
// resumed (u_n, u_{n-1}) equals stepping on without interruption, to round-off (u_{n-1} is
// recovered from the velocity, (u_n - u_{n-1}) / Δt, so only to the last bits).
TEST(ExplicitSolver, AResumedStateContinuesTheCentralDifference) {
  Block b;
  const hybrid::DhdConfig c = b.config(15);
  const std::vector<fem::ElementKind> kinds(b.mesh->num_tets(), fem::ElementKind::tled);
  fem::ElementSet e1(*b.mesh, kinds, c.material), e2(*b.mesh, kinds, c.material);
  dynamics::Scene scene = c.scene;
  scene.gravity = Eigen::Vector3d(0, 0, -9.81);
  dynamics::ExplicitOptions opt;
  opt.dt = 2e-4;
  opt.steps = 1000;
  opt.damping_alpha = 15;
  const auto masses = dynamics::lumped_mass(*b.mesh, c.material.elastic.density);
  dynamics::ExplicitSolver whole(e1, masses, scene, opt), resumed(e2, masses, scene, opt);
  whole.advance(300);
  const std::size_t n3 = 3 * static_cast<std::size_t>(b.mesh->num_nodes());
  std::vector<double> u(whole.displacement(), whole.displacement() + n3), v(n3), before(n3);
  whole.velocity(v.data());
  for (std::size_t q = 0; q < n3; ++q) before[q] = u[q] - opt.dt * v[q];
  resumed.set_resumed_state(u, before);
  resumed.reset();
  whole.advance(200);
  resumed.advance(200);
  double diff = 0, size = 0;
  for (std::size_t q = 0; q < n3; ++q) {
    diff = std::max(diff, std::abs(whole.displacement()[q] - resumed.displacement()[q]));
    size = std::max(size, std::abs(whole.displacement()[q]));
  }
  ASSERT_GT(size, 1e-4);
  EXPECT_LT(diff, 1e-12 * size) << diff << " of " << size;
  // The start-up step of a fresh start from the same (u, v) is only second-order accurate.
  fem::ElementSet e3(*b.mesh, kinds, c.material);
  dynamics::ExplicitSolver restarted(e3, masses, scene, opt);
  restarted.set_initial_state(u, v);
  restarted.reset();
  restarted.advance(200);
  double diff_restart = 0;
  for (std::size_t q = 0; q < n3; ++q) diff_restart = std::max(diff_restart, std::abs(whole.displacement()[q] - restarted.displacement()[q]));
  EXPECT_GT(diff_restart, 100 * diff);
}
