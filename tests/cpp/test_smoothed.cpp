// The selective smoothed-FEM tetrahedron (ElementKind::smoothed, fem/edge_smoothing.hpp) as
// physics: a homogeneous deformation is reproduced exactly (it is TLED there, the patch test);
// a rigid motion leaves no force and no energy; its forces are the gradient of its energy and
// the assembled tangent their derivative, next to the other kinds; the explicit engine's path
// equals the reference assembly; a damped explicit run settles on the static solution; the
// laterally confined block meets its closed form up to ν = 0.4999; at small ν it agrees with
// TLED, and as ν → 0.5 it does not stiffen the way TLED does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include <Eigen/Dense>

#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/dynamics/stable_step.hpp"
#include "softsim/dynamics/static_solver.hpp"
#include "softsim/fem/assembly.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/mesh/cuboid.hpp"

#include "support/assembly_checks.hpp"
#include "support/fields.hpp"
#include "support/scenes.hpp"

using namespace softsim;
using fem::ElementKind;
using material::NeoHookeanForm;

namespace {

using test_scenes::affine_field;
using test_scenes::expect_forces_are_the_energy_gradient_and_the_tangent_their_derivative;
using test_scenes::constraint;
using test_scenes::cuboid;
using test_scenes::gathered_forces;
using test_scenes::kPaper;
using test_scenes::max_abs;
using test_scenes::max_abs_diff;
using test_scenes::rough_field;
using test_scenes::run_explicit;

std::vector<ElementKind> all(const mesh::TetMesh& m, ElementKind kind) { return std::vector<ElementKind>(m.num_tets(), kind); }

// Smoothed elements with ANP, TLED and linear ones around them: interfaces of every pair.
std::vector<ElementKind> mixed_kinds(const mesh::TetMesh& m) {
  std::vector<ElementKind> kinds(m.num_tets());
  const auto& layer = m.element_tags.at("layer");
  for (int e = 0; e < m.num_tets(); ++e)
    kinds[e] = layer[e] == 0 ? ElementKind::linear : layer[e] == 3 ? ElementKind::tled
               : e % 7 == 0  ? ElementKind::anp
                             : ElementKind::smoothed;
  return kinds;
}

const material::ElasticParameters kSoft{5000.0, 0.49, 1000.0};

}  // namespace

TEST(Smoothed, HomogeneousDeformationIsReproducedExactlyAsByTled) {
  // Every edge-smoothed F_k is a weighted mean of equal F_e and every nodal J_a of equal J_e.
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);
  const fem::Material mat = fem::Material::make(kSoft, NeoHookeanForm::decoupled);
  fem::ElementSet smoothed(m, all(m, ElementKind::smoothed), mat);
  fem::ElementSet tled(m, all(m, ElementKind::tled), mat);
  Eigen::Matrix3d F;
  F << 0.8, 0.1, 0.0, -0.05, 1.1, 0.07, 0.02, 0.0, 0.9;
  const auto u = affine_field(m, F);
  const auto fs = gathered_forces(smoothed, u), ft = gathered_forces(tled, u);
  const double scale = max_abs(ft);
  ASSERT_GT(scale, 0);
  for (std::size_t q = 0; q < fs.size(); ++q) EXPECT_NEAR(fs[q], ft[q], 1e-11 * scale) << "dof " << q;
  const fem::Assembler as_s(m, all(m, ElementKind::smoothed), mat);
  const fem::Assembler as_t(m, all(m, ElementKind::tled), mat);
  Eigen::VectorXd fa;
  as_s.internal_forces(u.data(), fa);
  for (std::size_t q = 0; q < fs.size(); ++q) EXPECT_NEAR(fa[q], ft[q], 1e-11 * scale) << "dof " << q;
  EXPECT_NEAR(as_s.strain_energy(u.data()), as_t.strain_energy(u.data()), 1e-12 * as_t.strain_energy(u.data()));
}

TEST(Smoothed, RigidMotionLeavesNoForceAndNoEnergy) {
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  const fem::Material mat = fem::Material::make(kSoft, NeoHookeanForm::decoupled);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  std::vector<double> u = affine_field(m, R);
  for (int i = 0; i < m.num_nodes(); ++i) u[3 * i] += 0.004, u[3 * i + 2] -= 0.01;
  // The force scale: a 1 % stretch.
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  S(0, 0) = 1.01;
  fem::ElementSet set(m, all(m, ElementKind::smoothed), mat);
  const double scale = max_abs(gathered_forces(set, affine_field(m, S)));
  EXPECT_LT(max_abs(gathered_forces(set, u)), 1e-9 * scale);
  const fem::Assembler as(m, all(m, ElementKind::smoothed), mat);
  EXPECT_LT(std::abs(as.strain_energy(u.data())), 1e-9 * as.strain_energy(affine_field(m, S).data()));
}

TEST(Smoothed, ForcesAreTheGradientOfTheEnergyAndTheTangentTheirDerivative) {
  const auto m = cuboid(3, 3, 4, 0.03, 0.03, 0.04);
  const fem::Material mat = fem::Material::make(kSoft, NeoHookeanForm::decoupled);
  const fem::Assembler as(m, mixed_kinds(m), mat);
  const std::vector<double> u = rough_field(m, 7, 0.0008);
  expect_forces_are_the_energy_gradient_and_the_tangent_their_derivative(as, u);
}

TEST(Smoothed, ExplicitPathEqualsTheReferenceAssemblyInAMixedMesh) {
  const auto m = cuboid(4, 3, 4, 0.04, 0.03, 0.04);
  const fem::Material mat = fem::Material::make(kSoft, NeoHookeanForm::decoupled);
  const auto kinds = mixed_kinds(m);
  fem::ElementSet set(m, kinds, mat, 16);
  const fem::Assembler as(m, kinds, mat);
  const std::vector<double> u = rough_field(m, 5, 0.001);
  const auto f = gathered_forces(set, u);
  Eigen::VectorXd fr;
  as.internal_forces(u.data(), fr);
  const double scale = fr.lpNorm<Eigen::Infinity>();
  for (std::size_t q = 0; q < f.size(); ++q) EXPECT_NEAR(f[q], fr[q], 1e-11 * scale) << "dof " << q;
  std::vector<double> energy(set.padded_size()), volume_ratio(set.padded_size());
  double min_j = 1e300;
  int min_e = -1;
  set.energies(u.data(), 0, set.padded_size(), energy.data(), volume_ratio.data(), min_j, min_e);
  double w = set.nodal_volumetric_energy(volume_ratio.data());
  for (double x : energy) w += x;
  EXPECT_NEAR(w, as.strain_energy(u.data()), 1e-12 * w);
}

TEST(Smoothed, DampedRunSettlesOnTheStaticSolutionBitIdenticallyOnOneAndTwoThreads) {
  const auto m = cuboid(4, 3, 4, 0.04, 0.03, 0.04);
  const fem::Material mat = fem::Material::make(kPaper, NeoHookeanForm::decoupled);
  const auto kinds = mixed_kinds(m);
  auto [scene, opt] = test_scenes::damped_sheared_press(m);
  std::vector<std::vector<double>> results;
  for (int threads : {1, 2}) {
    opt.threads = threads;
    results.push_back(run_explicit(m, kinds, mat, scene, opt, {}, 16).displacement);
  }
  ASSERT_EQ(results[0].size(), results[1].size());
  EXPECT_EQ(0, std::memcmp(results[0].data(), results[1].data(), results[0].size() * sizeof(double)));
  const auto stat = dynamics::solve_static(m, kinds, mat, scene, {});
  EXPECT_LT(max_abs_diff(results[0], stat.displacement), 1e-9 * max_abs(stat.displacement));
}

TEST(Smoothed, ConfinedBlockMeetsItsClosedFormUpToTheIncompressibleLimit) {
  // A block in a frictionless rigid box (each side face held in its normal direction, the bottom
  // in z) compressed by 10 % from the top: F = diag(1, 1, s), J = s. The decoupled neo-Hookean
  // W = μ/2 (J^(−2/3) I₁ − 3) + K/2 (J − 1)² gives the top force
  //   A P₃₃ = A [μ/2 (2 s^(1/3) − 2/3 s^(−5/3) (2 + s²)) + K (s − 1)],
  // which grows like K as ν → 0.5: the element must follow it without locking up or off.
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  const double s = 0.9;
  for (double nu : {0.45, 0.49, 0.499, 0.4999}) {
    const material::ElasticParameters el{5000.0, nu, 1000.0};
    const fem::Material mat = fem::Material::make(el, NeoHookeanForm::decoupled);
    dynamics::Scene scene;
    scene.constraints = {constraint(m, "x_min", Eigen::Vector3d::Zero(), {true, false, false}),
                         constraint(m, "x_max", Eigen::Vector3d::Zero(), {true, false, false}),
                         constraint(m, "y_min", Eigen::Vector3d::Zero(), {false, true, false}),
                         constraint(m, "y_max", Eigen::Vector3d::Zero(), {false, true, false}),
                         constraint(m, "bottom", Eigen::Vector3d::Zero(), {false, false, true}),
                         constraint(m, "top", Eigen::Vector3d(0, 0, -(1 - s) * 0.03), {false, false, true})};
    dynamics::StaticOptions opt;
    opt.increments = 4;
    opt.tolerance = 1e-8;
    const auto r = dynamics::solve_static(m, all(m, ElementKind::smoothed), mat, scene, opt);
    const double mu = el.youngs_modulus / (2 * (1 + nu)), K = el.youngs_modulus / (3 * (1 - 2 * nu));
    const double P33 = 0.5 * mu * (2 * std::cbrt(s) - 2.0 / 3.0 * std::pow(s, -5.0 / 3.0) * (2 + s * s)) + K * (s - 1);
    const double expected = 0.03 * 0.03 * P33;
    EXPECT_NEAR(r.reactions[5].z(), expected, 1e-6 * std::abs(expected)) << "nu = " << nu;
  }
}

namespace {

// Block 6 × 6 × 3 cm of 6 × 6 × 3 cells, bottom clamped, its top nodes within 1 cm of the
// centre pushed down 0.3 mm (a bonded flat punch): the punch force (static).
double punch_force(ElementKind kind, double nu) {
  static const auto m = cuboid(6, 6, 3, 0.06, 0.06, 0.03);
  dynamics::DisplacementConstraint punch;
  punch.name = "punch";
  for (int i : m.node_sets.at("top"))
    if ((m.nodes[i] - Eigen::Vector3d(0.03, 0.03, 0.03)).norm() <= 0.0101) punch.nodes.push_back(i);
  punch.displacement = Eigen::Vector3d(0, 0, -0.0003);
  dynamics::Scene scene;
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero()), punch};
  const material::ElasticParameters el{5000.0, nu, 1000.0};
  dynamics::StaticOptions opt;
  opt.increments = 1;
  opt.tolerance = 1e-8;
  const auto r = dynamics::solve_static(m, all(m, kind), fem::Material::make(el, NeoHookeanForm::decoupled), scene, opt);
  return -r.reactions[1].z();
}

}  // namespace

// The force on a 4 cm cube's top face pushed by (2, 0, −6) mm, its bottom clamped, at ν = 0.2, on
// n × n × n cells.
Eigen::Vector3d press_force(ElementKind kind, int n) {
  const auto m = cuboid(n, n, n, 0.04, 0.04, 0.04);
  dynamics::Scene scene;
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero()),
                       constraint(m, "top", Eigen::Vector3d(0.002, 0, -0.006))};
  const material::ElasticParameters el{5000.0, 0.2, 1000.0};
  dynamics::StaticOptions opt;
  opt.increments = 2;
  return dynamics::solve_static(m, all(m, kind), fem::Material::make(el, NeoHookeanForm::decoupled), scene, opt)
      .reactions[1];
}

TEST(Smoothed, AgreesWithTledAtSmallPoissonRatio) {
  // Far from incompressibility both are consistent first-order discretisations of one problem:
  // they differ by their discretisation errors, a few per cent on these coarse grids, which shrink
  // with the cell size (slower than linearly: the clamped face's edges are stress singularities),
  // and the edge smoothing softens the over-stiff constant-strain element.
  const auto t2 = press_force(ElementKind::tled, 2), s2 = press_force(ElementKind::smoothed, 2);
  const auto t4 = press_force(ElementKind::tled, 4), s4 = press_force(ElementKind::smoothed, 4);
  const double d2 = (s2 - t2).norm() / t2.norm(), d4 = (s4 - t4).norm() / t4.norm();
  EXPECT_LT(d2, 0.03);
  EXPECT_LT(d4, 0.75 * d2) << "2 cells: " << d2 << ", 4 cells: " << d4;
  EXPECT_LT(s4.norm(), t4.norm());
}

TEST(Smoothed, DoesNotLockNearOneHalf) {
  // Near ν = 0.5 the constant-strain TLED tetrahedron locks (its punch force runs away from
  // ν = 0.49 to 0.4999) while the smoothed one grows about as the material's own stiffness
  // does (the converged punch force grows by under 10 % there, results/validation).
  const double grow_t = punch_force(ElementKind::tled, 0.4999) / punch_force(ElementKind::tled, 0.49);
  const double grow_s = punch_force(ElementKind::smoothed, 0.4999) / punch_force(ElementKind::smoothed, 0.49);
  EXPECT_GT(grow_t, 3.0);
  EXPECT_LT(grow_s, 1.5);
}
