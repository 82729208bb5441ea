// Dynamics as physics: lumped mass conserves mass (000 Fig. 7); the central-difference
// coefficients are 000 eq. 32; the critical step of 000 eq. 34 lies below the true stability
// limit 2/ω_max of the lumped system; undamped free vibration conserves energy; damped runs
// settle on the Newton static solution; 1 and 2 threads give bit-identical results; the
// static solver reproduces uniaxial compression of both neo-Hookean forms to 30 % and the
// weight of a hanging block; failures surface as the right error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "softsim/dynamics/central_difference.hpp"
#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/dynamics/node_selection.hpp"
#include "softsim/dynamics/stable_step.hpp"
#include "softsim/dynamics/static_solver.hpp"
#include "softsim/fem/assembly.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/material/uniaxial.hpp"
#include "softsim/mesh/cuboid.hpp"

#include "support/fields.hpp"
#include "support/scenes.hpp"

using namespace softsim;
using fem::ElementKind;

namespace {

using test_scenes::constraint;
using test_scenes::cuboid;
using test_scenes::kPaper;
using test_scenes::max_abs;
using test_scenes::max_abs_diff;
using test_scenes::run_explicit;

// Largest eigenvalue of M⁻¹K by power iteration (the stiffest mode of the lumped system).
double omega_max(const mesh::TetMesh& m, const fem::Material& mat) {
  const fem::Assembler as(m, std::vector<ElementKind>(m.num_tets(), ElementKind::linear), mat);
  Eigen::SparseMatrix<double> K = as.pattern();
  const std::vector<double> zero(3 * m.nodes.size(), 0.0);
  as.tangent(zero.data(), K);
  const std::vector<double> mass = dynamics::lumped_mass(m, mat.elastic.density);
  Eigen::VectorXd minv(K.rows());
  for (int i = 0; i < m.num_nodes(); ++i) minv.segment<3>(3 * i).setConstant(1.0 / mass[i]);
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(K.rows(), 1.0, 2.0);
  double lambda = 0;
  for (int it = 0; it < 3000; ++it) {
    const Eigen::VectorXd y = minv.cwiseProduct(K * x);
    lambda = x.dot(y) / x.dot(x);
    x = y.normalized();
  }
  return std::sqrt(lambda);
}

}  // namespace

TEST(LumpedMass, QuarterOfEachElementAndTotalMassPreserved) {
  const auto m = cuboid(3, 2, 2, 0.03, 0.02, 0.02);
  const auto mass = dynamics::lumped_mass(m, 1000.0);
  double total = 0;
  for (double x : mass) total += x;
  EXPECT_NEAR(total, 1000.0 * 0.03 * 0.02 * 0.02, 1e-15);
  // A corner node of the box belongs to one or two tets of its cell.
  std::vector<double> expected(m.num_nodes(), 0.0);
  for (const auto& t : m.tets)
    for (int a = 0; a < 4; ++a) expected[t[a]] += 250.0 * mesh::signed_volume(m, t);
  for (int i = 0; i < m.num_nodes(); ++i) EXPECT_NEAR(mass[i], expected[i], 1e-18);
}

TEST(CentralDifference, CoefficientsAreEquation32) {
  const double M = 0.3, alpha = 4.0, dt = 1e-3, D = alpha * M;
  const auto cd = dynamics::central_difference(M, alpha, dt);
  const double den = 2 * M * dt + D * dt * dt;  // 000 eq. 32 as written
  EXPECT_NEAR(cd.A, 2 * dt * dt * dt / den, 1e-18);
  EXPECT_NEAR(cd.B, 4 * M * dt / den, 1e-15);
  EXPECT_NEAR(cd.C, (2 * M * dt - D * dt * dt) / den, 1e-15);
  const auto undamped = dynamics::central_difference(M, 0.0, dt);
  EXPECT_NEAR(undamped.A, dt * dt / M, 1e-18);
  EXPECT_DOUBLE_EQ(undamped.B, 2.0);
  EXPECT_DOUBLE_EQ(undamped.C, 1.0);
}

TEST(CriticalStep, Equation34OnTheCuboidAndBelowTheTrueStabilityLimit) {
  const auto m = cuboid(4, 4, 3, 0.04, 0.04, 0.03);  // cubic cells of 1 cm
  const auto c = dynamics::critical_time_step(m, kPaper);
  // The corner tetrahedra of a cube of side h have altitude h/√3.
  EXPECT_NEAR(c.min_altitude, 0.01 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(c.dt, c.min_altitude / material::dilatational_wave_speed(kPaper), 1e-15);
  // The true limit of the lumped linear system is 2/ω_max. 000 eq. 34 estimates it within a few
  // per cent but is not a bound on this mesh (it exceeds it by about 3 %), which is why the
  // default safety factor is 0.9.
  const double limit = 2.0 / omega_max(m, fem::Material::make(kPaper, material::NeoHookeanForm::paper));
  EXPECT_NEAR(c.dt / limit, 1.0, 0.1);
  EXPECT_LT(0.9 * c.dt, limit);
}

TEST(CriticalStep, RequestAboveTheLimitIsRefusedUnlessForced) {
  dynamics::CriticalStep c;
  c.dt = 1e-3;
  EXPECT_THROW(dynamics::choose_time_step(c, 2e-3, 0.9, false), InputError);
  EXPECT_TRUE(dynamics::choose_time_step(c, 2e-3, 0.9, true).forced);
  EXPECT_DOUBLE_EQ(dynamics::choose_time_step(c, std::nullopt, 0.5, false).dt, 5e-4);
  EXPECT_DOUBLE_EQ(dynamics::choose_time_step(c, 8e-4, 0.9, false).dt, 8e-4);
}

TEST(Explicit, UndampedFreeVibrationConservesEnergy) {
  // Bottom clamped; released from the static shape of a 5 % lateral shear of the top face.
  // Bound: kinetic + strain energy stays within 0.2 % of its initial value over 3000 steps.
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  test_scenes::expect_free_vibration_conserves_energy(
      m, std::vector<ElementKind>(m.num_tets(), ElementKind::tled),
      fem::Material::make(kPaper, material::NeoHookeanForm::paper));
}

TEST(Explicit, ExternalWorkBalancesEnergyWithoutDamping) {
  // A ramped nodal force on the top face, no damping: kinetic + strain energy equals the work
  // done by the loads to 1e-4 (exact for a linear system with the half-step kinetic energy and
  // trapezoidal work; the TLED nonlinearity leaves a small remainder).
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::decoupled);
  dynamics::Scene scene;
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero())};
  dynamics::NodalLoad load;
  load.name = "top";
  load.nodes = m.node_sets.at("top");
  load.force_per_node = Eigen::Vector3d(0.0, 0.0005, -0.001);
  load.ramp.duration = 0.05;
  scene.loads = {load};
  dynamics::ExplicitOptions opt;
  opt.dt = 0.9 * dynamics::critical_time_step(m, kPaper).dt;
  opt.steps = 1000;
  opt.energy_interval = 50;
  const auto r = run_explicit(m, std::vector<ElementKind>(m.num_tets(), ElementKind::tled), mat, scene, opt);
  for (const auto& s : r.energies) {
    if (s.external_work <= 0) continue;
    EXPECT_NEAR(s.kinetic + s.strain, s.external_work, 1e-4 * s.external_work) << "t = " << s.time;
  }
  EXPECT_GT(r.energies.back().external_work, 0.0);
}

// Ramped gravity (Scene::gravity_ramp) is the same body force as a nodal load m_i g on every
// node with the same ramp (the workaround it replaces): displacements agree to round-off (the
// node update multiplies A m_i and g in another order) and so does the booked work; without
// damping kinetic + strain energy equals that work (trapezoidal booking while the ramp runs,
// G·Δu after it). A ramp of zero duration is the constant gravity, bit for bit.
TEST(Explicit, RampedGravityIsTheRampedNodalLoadOfEveryNode) {
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::decoupled);
  const std::vector<ElementKind> kinds(m.num_tets(), ElementKind::tled);
  const Eigen::Vector3d g(0.0, 2.0, -9.81);
  dynamics::ExplicitOptions opt;
  opt.dt = 0.9 * dynamics::critical_time_step(m, kPaper).dt;
  opt.steps = 1200;
  opt.energy_interval = 50;
  dynamics::Scene ramped;
  ramped.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero())};
  ramped.gravity = g;
  ramped.gravity_ramp.duration = 600 * opt.dt;  // ends mid-run: both bookings are exercised
  ramped.gravity_ramp.shape = dynamics::Ramp::Shape::smooth;
  dynamics::Scene loads;
  loads.constraints = ramped.constraints;
  const std::vector<double> mass = dynamics::lumped_mass(m, kPaper.density);
  for (int i = 0; i < m.num_nodes(); ++i) {
    dynamics::NodalLoad load;
    load.name = "node " + std::to_string(i);
    load.nodes = {i};
    load.force_per_node = mass[i] * g;
    load.ramp = ramped.gravity_ramp;
    loads.loads.push_back(load);
  }
  const auto a = run_explicit(m, kinds, mat, ramped, opt);
  const auto b = run_explicit(m, kinds, mat, loads, opt);
  EXPECT_LT(max_abs_diff(a.displacement, b.displacement), 1e-10 * max_abs(b.displacement));
  ASSERT_EQ(a.energies.size(), b.energies.size());
  for (std::size_t s = 0; s < a.energies.size(); ++s) {
    const auto& e = a.energies[s];
    EXPECT_NEAR(e.external_work, b.energies[s].external_work, 1e-9 * std::abs(b.energies.back().external_work))
        << "t = " << e.time;
    if (e.external_work > 0) EXPECT_NEAR(e.kinetic + e.strain, e.external_work, 1e-4 * e.external_work) << "t = " << e.time;
  }
  EXPECT_GT(a.energies.back().external_work, 0.0);
  // The ramp is felt: a sudden gravity ends the run elsewhere.
  dynamics::Scene constant = ramped;
  constant.gravity_ramp.duration = 0;
  dynamics::Scene plain = ramped;
  plain.gravity_ramp = dynamics::Ramp{};
  const auto c = run_explicit(m, kinds, mat, constant, opt);
  const auto d = run_explicit(m, kinds, mat, plain, opt);
  EXPECT_EQ(c.displacement, d.displacement);
  EXPECT_GT(max_abs_diff(c.displacement, a.displacement), 1e-3 * max_abs(c.displacement));
}

TEST(Explicit, DampedRunSettlesOnTheStaticSolution) {
  // Bottom clamped, top pushed down 15 % and sideways with a smooth ramp, mixed partition
  // (TLED top layers, linear and corotational below), α = 60/s.
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  std::vector<ElementKind> kinds(m.num_tets());
  const auto& layer = m.element_tags.at("layer");
  for (int e = 0; e < m.num_tets(); ++e)
    kinds[e] = layer[e] >= 2 ? ElementKind::tled : layer[e] == 1 ? ElementKind::corotational : ElementKind::linear;
  const auto [scene, opt] = test_scenes::damped_sheared_press(m);
  const auto dyn = run_explicit(m, kinds, mat, scene, opt);
  const auto stat = dynamics::solve_static(m, kinds, mat, scene, {});
  const double diff = max_abs_diff(dyn.displacement, stat.displacement);
  EXPECT_LT(diff, 1e-9 * max_abs(stat.displacement));
  // Reactions agree too (the explicit one leaves inertia out, which has died away).
  EXPECT_LT((dyn.reactions[1] - stat.reactions[1]).norm(), 1e-5 * stat.reactions[1].norm());
  EXPECT_GT(dyn.energies.back().dissipated, 0.0);
}

TEST(Explicit, OneAndTwoThreadsAreBitIdentical) {
  const auto m = cuboid(5, 4, 4, 0.05, 0.04, 0.04);  // 400 elements, groups not block multiples
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::decoupled);
  std::vector<ElementKind> kinds(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) kinds[e] = static_cast<ElementKind>((e * 7 + e / 13) % 3);
  dynamics::Scene scene;
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero()),
                       constraint(m, "top", Eigen::Vector3d(0.001, 0.002, -0.008))};
  scene.constraints[1].ramp.duration = 0.1;
  scene.gravity = Eigen::Vector3d(0, 0, -9.81);
  dynamics::ExplicitOptions opt;
  opt.dt = 0.9 * dynamics::critical_time_step(m, kPaper).dt;
  opt.steps = 120;
  opt.damping_alpha = 2.0;
  opt.energy_interval = 37;
  opt.trajectory_nodes = {5, 77, 140};
  // Small tiles, so that the two threads share the sweep and nodes wait across the barrier.
  opt.threads = 1;
  const auto a = run_explicit(m, kinds, mat, scene, opt, {}, 16);
  opt.threads = 2;
  const auto b = run_explicit(m, kinds, mat, scene, opt, {}, 16);
  opt.threads = 3;  // more parts than cores: each thread takes turns, results unchanged
  const auto c = run_explicit(m, kinds, mat, scene, opt, {}, 16);
  EXPECT_EQ(a.displacement, c.displacement);
  ASSERT_EQ(a.displacement.size(), b.displacement.size());
  EXPECT_EQ(0, std::memcmp(a.displacement.data(), b.displacement.data(), a.displacement.size() * sizeof(double)));
  EXPECT_EQ(0, std::memcmp(a.velocity.data(), b.velocity.data(), a.velocity.size() * sizeof(double)));
  ASSERT_EQ(a.energies.size(), b.energies.size());
  for (std::size_t s = 0; s < a.energies.size(); ++s) {
    EXPECT_EQ(a.energies[s].kinetic, b.energies[s].kinetic);
    EXPECT_EQ(a.energies[s].strain, b.energies[s].strain);
    EXPECT_EQ(a.energies[s].external_work, b.energies[s].external_work);
  }
  for (std::size_t j = 0; j < a.trajectories.size(); ++j)
    for (std::size_t s = 0; s < a.trajectories[j].size(); ++s) EXPECT_EQ(a.trajectories[j][s], b.trajectories[j][s]);
  EXPECT_GT(max_abs(a.displacement), 1e-3);
}

// The thread split follows approximate cost estimates (ElementSet::relative_cost, tile_cost):
// every element kind present, ANP with its nodal-pressure pre-pass included, and splits into
// 1 to 7 parts over tiles of two sizes must all give the same bits.
TEST(Explicit, EveryKindAndEveryThreadSplitGiveTheSameBits) {
  const auto m = cuboid(5, 4, 4, 0.05, 0.04, 0.04);  // 400 elements
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::decoupled);
  std::vector<ElementKind> kinds(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) kinds[e] = static_cast<ElementKind>((e * 5 + e / 11) % fem::kNumElementKinds);
  for (int k = 0; k < fem::kNumElementKinds; ++k)
    ASSERT_GT(std::count(kinds.begin(), kinds.end(), static_cast<ElementKind>(k)), 0) << fem::kind_name(static_cast<ElementKind>(k));
  dynamics::Scene scene;
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero()),
                       constraint(m, "top", Eigen::Vector3d(0.002, -0.001, -0.006))};
  scene.constraints[1].ramp.duration = 0.05;
  dynamics::ExplicitOptions opt;
  opt.dt = 0.8 * dynamics::critical_time_step(m, kPaper).dt;
  opt.steps = 90;
  opt.damping_alpha = 1.0;
  opt.energy_interval = 17;
  opt.threads = 1;
  const auto ref = run_explicit(m, kinds, mat, scene, opt, {}, 16);
  EXPECT_GT(max_abs(ref.displacement), 1e-3);
  for (int tile_nodes : {16, 64})
    for (int threads : {1, 2, 3, 4, 7}) {
      opt.threads = threads;
      const auto r = run_explicit(m, kinds, mat, scene, opt, {}, tile_nodes);
      ASSERT_EQ(r.displacement.size(), ref.displacement.size());
      EXPECT_EQ(0, std::memcmp(r.displacement.data(), ref.displacement.data(), r.displacement.size() * sizeof(double)))
          << threads << " threads, tiles of " << tile_nodes << " nodes";
      ASSERT_EQ(r.energies.size(), ref.energies.size());
      for (std::size_t s = 0; s < r.energies.size(); ++s) {
        EXPECT_EQ(r.energies[s].strain, ref.energies[s].strain) << threads << " threads, sample " << s;
        EXPECT_EQ(r.energies[s].kinetic, ref.energies[s].kinetic) << threads << " threads, sample " << s;
      }
    }
}

// Intervals up to the int range are accepted by the config: the next energy sample or snapshot
// then lies beyond it, and the run must still stop at its last step.
TEST(Explicit, IntervalsNearTheIntRangeEndTheRunAtItsLastStep) {
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  const std::vector<ElementKind> kinds(m.num_tets(), ElementKind::tled);
  dynamics::Scene scene;
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero()),
                       constraint(m, "top", Eigen::Vector3d(0, 0, -0.001))};
  dynamics::ExplicitOptions opt;
  opt.dt = 0.9 * dynamics::critical_time_step(m, kPaper).dt;
  opt.steps = 30;
  const auto reference = run_explicit(m, kinds, mat, scene, opt);
  opt.energy_interval = std::numeric_limits<int>::max();
  opt.snapshot_interval = std::numeric_limits<int>::max();
  fem::ElementSet set(m, kinds, mat);
  dynamics::ExplicitSolver solver(set, dynamics::lumped_mass(m, mat.elastic.density), scene, opt);
  std::vector<int> snapshots;
  const auto wide = solver.run([&](int step, double, const std::vector<double>&, const std::vector<double>&) {
    snapshots.push_back(step);
  });
  EXPECT_EQ(wide.steps, 30);
  EXPECT_EQ(wide.displacement, reference.displacement);
  EXPECT_EQ(snapshots, std::vector<int>{0});
  ASSERT_EQ(wide.energies.size(), 2u);  // after the first and the last step
  EXPECT_EQ(wide.energies.back().time, reference.energies.back().time);
}

TEST(Explicit, UnstableStepIsANumericalError) {
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  dynamics::Scene scene;
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero()),
                       constraint(m, "top", Eigen::Vector3d(0, 0, -0.001))};
  dynamics::ExplicitOptions opt;
  opt.dt = 3.0 * 2.0 / omega_max(m, mat);  // three times the true limit
  opt.steps = 2000;
  opt.energy_interval = 20;
  for (ElementKind kind : {ElementKind::linear, ElementKind::tled}) {
    try {
      run_explicit(m, std::vector<ElementKind>(m.num_tets(), kind), mat, scene, opt);
      ADD_FAILURE() << "an unstable run must fail";
    } catch (const NumericalError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("explicit step"), std::string::npos) << msg;
      EXPECT_TRUE(msg.find("energy") != std::string::npos || msg.find("inverted") != std::string::npos ||
                  msg.find("not finite") != std::string::npos)
          << msg;
    }
  }
}

class Inversion : public ::testing::TestWithParam<ElementKind> {};

TEST_P(Inversion, InvertedElementNamesStepElementAndJ) {
  // A huge force on one free corner drives it through the opposite face within a few steps; the
  // failure must name the element and J, not a non-finite displacement one step later.
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  dynamics::Scene scene;
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero())};
  dynamics::NodalLoad push;
  push.name = "corner";
  push.nodes = {m.num_nodes() - 1};  // top corner (x max, y max, z max)
  push.force_per_node = Eigen::Vector3d(0, 0, -50.0);
  scene.loads = {push};
  dynamics::ExplicitOptions opt;
  opt.dt = 0.9 * dynamics::critical_time_step(m, kPaper).dt;
  opt.steps = 200;
  const std::string kind = fem::kind_name(GetParam());
  try {
    run_explicit(m, std::vector<ElementKind>(m.num_tets(), GetParam()), mat, scene, opt);
    ADD_FAILURE() << "the element must invert";
  } catch (const NumericalError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("explicit step"), std::string::npos) << msg;
    EXPECT_NE(msg.find("(" + kind + ") is inverted: J = "), std::string::npos) << msg;
  }
}

INSTANTIATE_TEST_SUITE_P(NonlinearKinds, Inversion,
                         ::testing::Values(ElementKind::tled, ElementKind::corotational, ElementKind::anp),
                         [](const auto& info) { return std::string(fem::kind_name(info.param)); });

class UniaxialCompression : public ::testing::TestWithParam<material::NeoHookeanForm> {};

TEST_P(UniaxialCompression, ThirtyPercentMatchesTheHomogeneousSolution) {
  // Symmetry planes x = 0, y = 0, z = 0 and the top pushed to 70 % of the height; lateral faces
  // free. Compared: the lateral stretch of the free corner and the top reaction force.
  const double L = 0.02, H = 0.03;
  const auto m = cuboid(2, 2, 3, L, L, H);
  const fem::Material mat = fem::Material::make(kPaper, GetParam());
  dynamics::Scene scene;
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero(), {false, false, true}),
                       constraint(m, "x_min", Eigen::Vector3d::Zero(), {true, false, false}),
                       constraint(m, "y_min", Eigen::Vector3d::Zero(), {false, true, false}),
                       constraint(m, "top", Eigen::Vector3d(0, 0, -0.3 * H), {false, false, true})};
  dynamics::StaticOptions opt;
  opt.increments = 6;
  const auto r = dynamics::solve_static(m, std::vector<ElementKind>(m.num_tets(), ElementKind::tled), mat, scene, opt);
  const auto exact = material::uniaxial_neo_hookean(std::get<material::NeoHookean>(mat.law), 0.7);
  const int corner = m.num_nodes() - 1;  // (L, L, H)
  const double lateral = 1.0 + r.displacement[3 * corner] / L;
  // Required: 0.5 %. The state is homogeneous, which linear tetrahedra represent exactly, so the
  // finite elements must in fact agree to the Newton tolerance; 1e-8 is asserted.
  const double tol = 1e-8;
  EXPECT_NEAR(lateral, exact.lateral_stretch, tol * exact.lateral_stretch);
  EXPECT_NEAR(1.0 + r.displacement[3 * corner + 1] / L, exact.lateral_stretch, tol * exact.lateral_stretch);
  // The top plate's force on the block is the nominal stress P33 times the reference area.
  const double force = r.reactions[3].z();
  EXPECT_NEAR(force, exact.nominal_stress * L * L, tol * std::abs(exact.nominal_stress) * L * L);
  EXPECT_GT(lateral, 1.05);
}

INSTANTIATE_TEST_SUITE_P(BothForms, UniaxialCompression,
                         ::testing::Values(material::NeoHookeanForm::paper, material::NeoHookeanForm::decoupled),
                         [](const auto& info) { return material::form_name(info.param); });

TEST(Static, HangingBlockReactionIsItsWeight) {
  const auto m = cuboid(3, 3, 4, 0.03, 0.03, 0.04);
  for (ElementKind kind : {ElementKind::linear, ElementKind::tled, ElementKind::corotational}) {
    const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
    dynamics::Scene scene;
    scene.constraints = {constraint(m, "top", Eigen::Vector3d::Zero())};
    scene.gravity = Eigen::Vector3d(0, 0, -9.81);
    const auto r = dynamics::solve_static(m, std::vector<ElementKind>(m.num_tets(), kind), mat, scene, {});
    const double weight = kPaper.density * 0.03 * 0.03 * 0.04 * 9.81;
    // The support holds the block up: its force on the body is +weight.
    EXPECT_NEAR(r.reactions[0].z(), weight, 1e-8 * weight) << fem::kind_name(kind);
    EXPECT_NEAR(r.reactions[0].x(), 0.0, 1e-8 * weight);
    EXPECT_LT(r.displacement[3 * 0 + 2], 0.0) << "the free bottom sags";
  }
}

TEST(Static, ProbeSpringForceIsBalancedByTheSupports) {
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  dynamics::Scene scene;
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero())};
  scene.has_probe = true;
  scene.probe.node = m.node_sets.at("top")[5];
  scene.probe.stiffness = 50.0;
  scene.probe.displacement = Eigen::Vector3d(0.001, 0, -0.004);
  const auto r = dynamics::solve_static(m, std::vector<ElementKind>(m.num_tets(), ElementKind::tled), mat, scene, {});
  EXPECT_LT((r.reactions[0] + r.probe_force).norm(), 1e-8 * r.probe_force.norm());
  // The node lags behind the tip: the spring is stretched, and pulls downwards.
  EXPECT_LT(r.probe_force.z(), 0.0);
  EXPECT_GT(r.displacement[3 * scene.probe.node + 2], -0.004);
}

TEST(Static, UnconstrainedBodyIsASingularSystem) {
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  dynamics::Scene scene;
  scene.gravity = Eigen::Vector3d(0, 0, -9.81);
  EXPECT_THROW(dynamics::solve_static(m, std::vector<ElementKind>(m.num_tets(), ElementKind::linear),
                                      fem::Material::make(kPaper, material::NeoHookeanForm::paper), scene, {}),
               NumericalError);
}

TEST(Static, LinearMaterialIsOneSolveEvenWhenTheGeometryInverts) {
  // The top of a 3 cm cube is pushed down 5 cm, through the bottom: the mapped geometry is
  // inside out, yet for small-strain elements (000 eqs. 4–12) u = K⁻¹R is the solution. The
  // reference is an independent dense solve of the partitioned system K_ff u_f = −K_fc u_c.
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  const std::vector<ElementKind> kinds(m.num_tets(), ElementKind::linear);
  dynamics::Scene scene;
  const Eigen::Vector3d push(0.004, 0, -0.05);
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero()), constraint(m, "top", push)};
  const auto r = dynamics::solve_static(m, kinds, mat, scene, {});
  EXPECT_TRUE(r.linear_solve);
  ASSERT_EQ(r.iterations.size(), 1u) << "one increment";

  const fem::Assembler assembler(m, kinds, mat);
  EXPECT_LT(assembler.min_volume_ratio(r.displacement.data()), 0.0) << "the solution inverts the geometry";
  const int n3 = 3 * m.num_nodes();
  Eigen::SparseMatrix<double> Ks = assembler.pattern();
  const std::vector<double> zero(n3, 0.0);
  assembler.tangent(zero.data(), Ks);
  const Eigen::MatrixXd K(Ks);
  Eigen::VectorXd uc = Eigen::VectorXd::Zero(n3);
  std::vector<char> fixed(n3, 0);
  for (const char* set : {"bottom", "top"})
    for (int node : m.node_sets.at(set))
      for (int k = 0; k < 3; ++k) {
        fixed[3 * node + k] = 1;
        uc[3 * node + k] = std::string(set) == "top" ? push[k] : 0.0;
      }
  std::vector<int> free;
  for (int q = 0; q < n3; ++q)
    if (!fixed[q]) free.push_back(q);
  const int nf = static_cast<int>(free.size());
  Eigen::MatrixXd Kff(nf, nf);
  Eigen::VectorXd rhs(nf);
  const Eigen::VectorXd Kuc = K * uc;
  for (int a = 0; a < nf; ++a) {
    rhs[a] = -Kuc[free[a]];
    for (int b = 0; b < nf; ++b) Kff(a, b) = K(free[a], free[b]);
  }
  const Eigen::VectorXd uf = Kff.ldlt().solve(rhs);
  double diff = 0;
  for (int a = 0; a < nf; ++a) diff = std::max(diff, std::abs(r.displacement[free[a]] - uf[a]));
  EXPECT_LT(diff, 1e-9 * push.norm());
  for (int q = 0; q < n3; ++q)
    if (fixed[q]) EXPECT_EQ(r.displacement[q], uc[q]);
  // The nonlinear (TLED) model of the same scene cannot pass through inversion.
  EXPECT_THROW(dynamics::solve_static(m, std::vector<ElementKind>(m.num_tets(), ElementKind::tled), mat, scene, {}),
               NumericalError);
}

// ---- the stepping interface: one loop, however it is driven ----

namespace {

// A mixed partition under gravity, a ramped prescribed displacement, a ramped probe and damping:
// everything the special-node update handles.
struct SteppingScene {
  mesh::TetMesh mesh = cuboid(4, 3, 3, 0.04, 0.03, 0.03);
  fem::Material material = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  std::vector<ElementKind> kinds;
  dynamics::Scene scene;
  dynamics::ExplicitOptions options;
  SteppingScene() {
    kinds.resize(mesh.num_tets());
    for (int e = 0; e < mesh.num_tets(); ++e) kinds[e] = static_cast<ElementKind>(e % 3);
    scene.constraints = {constraint(mesh, "bottom", Eigen::Vector3d::Zero()),
                         constraint(mesh, "top", Eigen::Vector3d(0.001, 0.0, -0.004))};
    scene.constraints[1].ramp.duration = 0.06;
    scene.constraints[1].ramp.shape = dynamics::Ramp::Shape::smooth;
    scene.gravity = Eigen::Vector3d(0, 0, -9.81);
    scene.has_probe = true;
    scene.probe.node = dynamics::nearest_node(mesh, Eigen::Vector3d(0.04, 0.01, 0.01));  // x_max face, free
    scene.probe.stiffness = 40.0;
    scene.probe.displacement = Eigen::Vector3d(0.002, 0.0, 0.0);
    scene.probe.ramp.duration = 0.05;
    options.dt = 0.9 * dynamics::critical_time_step(mesh, kPaper).dt;
    options.steps = 150;
    options.damping_alpha = 5.0;
    options.energy_interval = 20;
  }
};

void expect_same_state(const dynamics::ExplicitSolver& a, const dynamics::ExplicitSolver& b) {
  const int n3 = 3 * a.num_nodes();
  EXPECT_EQ(a.steps_done(), b.steps_done());
  EXPECT_EQ(0, std::memcmp(a.displacement(), b.displacement(), n3 * sizeof(double)));
  ASSERT_EQ(a.energies().size(), b.energies().size());
  for (std::size_t s = 0; s < a.energies().size(); ++s) {
    EXPECT_EQ(a.energies()[s].kinetic, b.energies()[s].kinetic);
    EXPECT_EQ(a.energies()[s].strain, b.energies()[s].strain);
    EXPECT_EQ(a.energies()[s].external_work, b.energies()[s].external_work) << "sample " << s;
  }
}

}  // namespace

TEST(Stepping, AdvanceInChunksEqualsTheWholeRun) {
  SteppingScene s;
  fem::ElementSet set_a(s.mesh, s.kinds, s.material), set_b(s.mesh, s.kinds, s.material);
  const auto masses = dynamics::lumped_mass(s.mesh, s.material.elastic.density);
  dynamics::ExplicitSolver whole(set_a, masses, s.scene, s.options);
  const dynamics::ExplicitResult r = whole.run();
  dynamics::ExplicitSolver chunks(set_b, masses, s.scene, s.options);
  for (int n : {1, 0, 19, 7, 50, 73}) chunks.advance(n);
  expect_same_state(whole, chunks);
  EXPECT_EQ(r.displacement, std::vector<double>(chunks.displacement(), chunks.displacement() + 3 * s.mesh.num_nodes()));
  EXPECT_EQ(r.reactions, chunks.reactions());
  EXPECT_EQ(r.probe_force.size(), 150u);
  std::vector<double> v(3 * s.mesh.num_nodes());
  chunks.velocity(v.data());
  EXPECT_EQ(r.velocity, v);
  // A reset returns to t = 0: the same run again, bit for bit.
  chunks.reset();
  EXPECT_EQ(chunks.steps_done(), 0);
  chunks.advance(150);
  expect_same_state(whole, chunks);
}

// Moving the prescribed displacement and the probe tip between steps, to the values their ramps
// would have, is the same scheme as the ramps: the same state and energy balance, bit for bit
// (000 eq. 33 sees only the values, not where they come from).
TEST(Stepping, DrivingBetweenStepsEqualsTheScheduledRamps) {
  SteppingScene s;
  fem::ElementSet set_a(s.mesh, s.kinds, s.material), set_b(s.mesh, s.kinds, s.material);
  const auto masses = dynamics::lumped_mass(s.mesh, s.material.elastic.density);
  dynamics::ExplicitSolver ramped(set_a, masses, s.scene, s.options);
  ramped.advance(s.options.steps);
  dynamics::ExplicitSolver driven(set_b, masses, s.scene, s.options);
  const dynamics::DisplacementConstraint top = s.scene.constraints[1];
  const dynamics::ProbeSpring probe = s.scene.probe;
  const double dt = s.options.dt;
  for (int n = 0; n < s.options.steps; ++n) {
    // Step n → n + 1 imposes the constraint at t_n + Δt and applies the probe spring at t_n.
    driven.set_prescribed_displacement(1, top.displacement * top.ramp.at(n * dt + dt));
    driven.set_probe_tip(probe.displacement * probe.ramp.at(n * dt));
    driven.advance(1);
  }
  expect_same_state(ramped, driven);
  EXPECT_EQ(ramped.probe_force(), driven.probe_force());
  EXPECT_GT(ramped.energies().back().external_work, 0.0);
}

// The probe force read between steps is the spring law at the current state, and a probe held
// still in a damped body settles: the supports then carry the probe's pull (statics: the
// reaction F_int − R on the supports is −f, the internal forces summing to zero).
TEST(Stepping, ProbeForceBalancesTheSupportsOnceSettled) {
  SteppingScene s;
  s.scene.gravity.setZero();
  s.scene.constraints.resize(1);  // bottom only
  s.options.damping_alpha = 80.0;
  fem::ElementSet set(s.mesh, s.kinds, s.material);
  dynamics::ExplicitSolver solver(set, dynamics::lumped_mass(s.mesh, s.material.elastic.density), s.scene, s.options);
  solver.advance(3000);
  const Eigen::Vector3d f = solver.probe_force();
  const int i = s.scene.probe.node;
  const Eigen::Vector3d u(solver.displacement()[3 * i], solver.displacement()[3 * i + 1], solver.displacement()[3 * i + 2]);
  EXPECT_EQ(f, s.scene.probe.stiffness * (s.scene.probe.displacement - u));
  const Eigen::Vector3d support = solver.reactions()[0];
  EXPECT_GT(f.norm(), 1e-3);
  EXPECT_LT((support + f).norm(), 1e-6 * f.norm());
}

TEST(Stepping, BadDrivingInputIsRefused) {
  SteppingScene s;
  s.scene.has_probe = false;
  fem::ElementSet set(s.mesh, s.kinds, s.material);
  dynamics::ExplicitSolver solver(set, dynamics::lumped_mass(s.mesh, s.material.elastic.density), s.scene, s.options);
  EXPECT_THROW(solver.set_prescribed_displacement(2, Eigen::Vector3d::Zero()), InputError);
  EXPECT_THROW(solver.set_prescribed_displacement(1, Eigen::Vector3d(NAN, 0, 0)), InputError);
  EXPECT_THROW(solver.set_probe_tip(Eigen::Vector3d::Zero()), InputError);
  EXPECT_THROW(solver.advance(-1), InputError);
}

// ---- held nodes: fixed in all three components, left out of the node update ----

namespace {

// SteppingScene plus a face held at a constant non-zero value, a face held in x only (not held:
// its other components are integrated), a load on held nodes and trajectories of held and free
// nodes; `skip` chooses whether held nodes are left out of the update.
dynamics::ExplicitOptions held_scene(SteppingScene& s, bool skip) {
  dynamics::DisplacementConstraint side = constraint(s.mesh, "x_min", Eigen::Vector3d(0.0005, -0.0002, 0.0003));
  dynamics::DisplacementConstraint slide = constraint(s.mesh, "y_min", Eigen::Vector3d::Zero());
  slide.components = {true, false, false};
  s.scene.constraints.push_back(side);
  s.scene.constraints.push_back(slide);
  dynamics::NodalLoad on_held;
  on_held.name = "on the bottom";
  on_held.nodes = s.mesh.node_sets.at("bottom");
  on_held.force_per_node = Eigen::Vector3d(0.01, 0.0, -0.02);
  s.scene.loads.push_back(on_held);
  dynamics::ExplicitOptions opt = s.options;
  opt.trajectory_nodes = {s.mesh.node_sets.at("bottom").front(), s.mesh.node_sets.at("x_min").back(),
                          s.mesh.node_sets.at("y_min").back(), s.scene.probe.node};
  opt.trajectory_interval = 10;
  opt.skip_held_nodes = skip;
  return opt;
}

}  // namespace

// Leaving the held nodes out of the update changes nothing: every free component, energy,
// trajectory, reaction and probe force equals the full update bit for bit, and the held nodes
// keep their prescribed values exactly.
TEST(HeldNodes, SkippingThemEqualsTheFullUpdateAndTheyHoldTheirValues) {
  for (int threads : {1, 2}) {
    SteppingScene a_scene, b_scene;
    dynamics::ExplicitOptions opt_full = held_scene(a_scene, false), opt_skip = held_scene(b_scene, true);
    opt_full.threads = opt_skip.threads = threads;
    fem::ElementSet set_a(a_scene.mesh, a_scene.kinds, a_scene.material),
        set_b(b_scene.mesh, b_scene.kinds, b_scene.material);
    const auto masses = dynamics::lumped_mass(a_scene.mesh, a_scene.material.elastic.density);
    dynamics::ExplicitSolver full(set_a, masses, a_scene.scene, opt_full);
    dynamics::ExplicitSolver skip(set_b, masses, b_scene.scene, opt_skip);
    const dynamics::ExplicitResult r_full = full.run(), r_skip = skip.run();
    expect_same_state(full, skip);
    EXPECT_EQ(0, std::memcmp(r_full.displacement.data(), r_skip.displacement.data(),
                             r_full.displacement.size() * sizeof(double)));
    EXPECT_EQ(r_full.velocity, r_skip.velocity);
    EXPECT_EQ(r_full.trajectories, r_skip.trajectories);
    EXPECT_EQ(r_full.reactions, r_skip.reactions);
    EXPECT_EQ(r_full.probe_force, r_skip.probe_force);
    EXPECT_GT(max_abs(r_skip.displacement), 1e-3);
    // The held nodes: zero on the bottom, the constant value on x_min (where the faces meet, the
    // later constraint wins per component); the y_min face moves in y and z.
    const dynamics::DisplacementConstraint& side = b_scene.scene.constraints[2];
    for (int i : b_scene.mesh.node_sets.at("x_min"))
      for (int k = 0; k < 3; ++k)
        if (!(k == 0 && std::count(b_scene.mesh.node_sets.at("y_min").begin(), b_scene.mesh.node_sets.at("y_min").end(), i)))
          EXPECT_EQ(r_skip.displacement[3 * i + k], side.displacement[k]) << "node " << i;
    const auto& bottom = b_scene.mesh.node_sets.at("bottom");
    const auto& xmin = b_scene.mesh.node_sets.at("x_min");
    for (int i : bottom)
      if (!std::count(xmin.begin(), xmin.end(), i))
        for (int k = 0; k < 3; ++k) EXPECT_EQ(r_skip.displacement[3 * i + k], 0.0) << "node " << i;
    double y_motion = 0;
    for (int i : b_scene.mesh.node_sets.at("y_min")) y_motion = std::max(y_motion, std::abs(r_skip.displacement[3 * i + 2]));
    EXPECT_GT(y_motion, 1e-5);
  }
}

// A held constraint driven between steps (a haptic tool taking a fixed node) stops being held:
// its nodes are updated again and the driven run equals the full update bit for bit.
TEST(HeldNodes, ADrivenConstraintIsNoLongerSkipped) {
  SteppingScene a_scene, b_scene;
  dynamics::ExplicitOptions opt_full = held_scene(a_scene, false), opt_skip = held_scene(b_scene, true);
  fem::ElementSet set_a(a_scene.mesh, a_scene.kinds, a_scene.material),
      set_b(b_scene.mesh, b_scene.kinds, b_scene.material);
  const auto masses = dynamics::lumped_mass(a_scene.mesh, a_scene.material.elastic.density);
  dynamics::ExplicitSolver full(set_a, masses, a_scene.scene, opt_full);
  dynamics::ExplicitSolver skip(set_b, masses, b_scene.scene, opt_skip);
  for (dynamics::ExplicitSolver* s : {&full, &skip}) {
    s->advance(40);
    s->set_prescribed_displacement(2, Eigen::Vector3d(0.001, 0.0, 0.0));  // x_min, held so far
    s->advance(60);
  }
  expect_same_state(full, skip);
  EXPECT_EQ(full.reactions(), skip.reactions());
  const auto& ymin = b_scene.mesh.node_sets.at("y_min");
  for (int i : b_scene.mesh.node_sets.at("x_min"))
    if (!std::count(ymin.begin(), ymin.end(), i)) EXPECT_EQ(skip.displacement()[3 * i], 0.001) << "node " << i;
}
