// The critical step from the largest eigenvalue (dynamics/spectral_step.hpp) against a dense
// eigenvalue computation of the same lumped system: within the tolerance it states, above the
// true limit 2/ω_max by less than that tolerance, on a regular mesh and on one with a sliver,
// where 000 eq. 34's altitude estimate is far too small.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/dynamics/spectral_step.hpp"
#include "softsim/dynamics/stable_step.hpp"
#include "softsim/fem/assembly.hpp"
#include "softsim/hybrid/dhd_scene.hpp"
#include "softsim/io/errors.hpp"

#include "support/scenes.hpp"

using namespace softsim;
using fem::ElementKind;
using test_scenes::cuboid;
using test_scenes::kPaper;

namespace {

dynamics::Scene bottom_fixed(const mesh::TetMesh& m) {
  dynamics::Scene scene;
  dynamics::DisplacementConstraint c;
  c.name = "bottom";
  c.nodes = m.node_sets.at("bottom");
  scene.constraints = {c};
  return scene;
}

// 2/ω_max with ω_max² the largest eigenvalue of M⁻¹K on the free dofs, densely.
double exact_limit(const mesh::TetMesh& m, const std::vector<ElementKind>& kinds, const fem::Material& mat,
                   const dynamics::Scene& scene) {
  const fem::Assembler as(m, kinds, mat);
  Eigen::SparseMatrix<double> K = as.pattern();
  const std::vector<double> zero(3 * m.nodes.size(), 0.0);
  as.tangent(zero.data(), K);
  const std::vector<double> mass = dynamics::lumped_mass(m, mat.elastic.density);
  const auto mask = dynamics::constrained_mask(dynamics::resolve_constraints(scene, m.num_nodes()), m.num_nodes());
  std::vector<int> free;
  for (int q = 0; q < 3 * m.num_nodes(); ++q)
    if (!mask[q]) free.push_back(q);
  const Eigen::MatrixXd Kd(K);
  Eigen::MatrixXd A(free.size(), free.size());
  for (std::size_t i = 0; i < free.size(); ++i)
    for (std::size_t j = 0; j < free.size(); ++j)
      A(i, j) = Kd(free[i], free[j]) / std::sqrt(mass[free[i] / 3] * mass[free[j] / 3]);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, Eigen::EigenvaluesOnly);
  return 2.0 / std::sqrt(eig.eigenvalues().maxCoeff());
}

// One interior node moved a share s of the way to the plane of the opposite face of one of its tets.
mesh::TetMesh with_sliver(mesh::TetMesh m, double s) {
  const Eigen::Vector3d centre = 0.5 * (m.nodes.front() + m.nodes.back());
  const auto& boundary = m.node_sets.at("boundary");
  int node = -1;
  for (int i = 0; i < m.num_nodes(); ++i)
    if (!std::binary_search(boundary.begin(), boundary.end(), i) &&
        (node < 0 || (m.nodes[i] - centre).norm() < (m.nodes[node] - centre).norm()))
      node = i;
  for (const auto& t : m.tets) {
    if (std::find(t.begin(), t.end(), node) == t.end()) continue;
    std::vector<int> face;
    for (int a : t)
      if (a != node) face.push_back(a);
    const Eigen::Vector3d n = (m.nodes[face[1]] - m.nodes[face[0]]).cross(m.nodes[face[2]] - m.nodes[face[0]]).normalized();
    const Eigen::Vector3d foot = m.nodes[node] - (m.nodes[node] - m.nodes[face[0]]).dot(n) * n;
    m.nodes[node] += s * (foot - m.nodes[node]);
    break;
  }
  return m;
}

// λ = ρ + residual ≤ λ_max (1 + tolerance) always (ρ ≤ λ_max): 2/√λ ≥ exact / √(1 + tolerance).
// Above the limit it may lie only where the top eigenvalues cluster closer than the residual
// (ρ then sits among them), and by less than the tolerance: the promise of spectral_step.hpp.
void expect_within_tolerance(const dynamics::SpectralStep& s, double exact) {
  EXPECT_TRUE(s.converged);
  EXPECT_LE(s.dt, exact * (1 + s.tolerance));
  EXPECT_GE(s.dt, exact / std::sqrt(1 + s.tolerance) * (1 - 1e-12));
}

}  // namespace

TEST(SpectralStep, PowerIterationMatchesTheDenseLimitOnARegularMesh) {
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  const std::vector<ElementKind> kinds(m.num_tets(), ElementKind::tled);
  const auto scene = bottom_fixed(m);
  const double exact = exact_limit(m, kinds, mat, scene);
  const auto s = dynamics::power_iteration_step(m, kinds, mat, scene);
  expect_within_tolerance(s, exact);
  // 000 eq. 34 is a bound of the same limit, within a small factor on a regular mesh.
  const double altitude = dynamics::critical_time_step(m, kPaper).dt;
  EXPECT_GT(exact / altitude, 0.5);
  EXPECT_LT(exact / altitude, 2.0);
}

TEST(SpectralStep, ATighterToleranceGetsCloser) {
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  const std::vector<ElementKind> kinds(m.num_tets(), ElementKind::linear);
  const auto scene = bottom_fixed(m);
  const double exact = exact_limit(m, kinds, mat, scene);
  dynamics::PowerIterationOptions o;
  o.tolerance = 1e-4;
  const auto s = dynamics::power_iteration_step(m, kinds, mat, scene, nullptr, o);
  expect_within_tolerance(s, exact);
  EXPECT_NEAR(s.dt / exact, 1.0, 1e-4);
}

// The case 000 eq. 34 handles worst: one sliver (its altitude 1/1000 of the others') sets the
// altitude estimate for the whole mesh, while the lumped system's limit hardly moves.
TEST(SpectralStep, OnASliverPowerIterationFindsTheLimitTheAltitudeEstimateMisses) {
  const auto m = with_sliver(cuboid(4, 4, 3, 0.04, 0.04, 0.03), 0.999);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  const std::vector<ElementKind> kinds(m.num_tets(), ElementKind::tled);
  const auto scene = bottom_fixed(m);
  const double exact = exact_limit(m, kinds, mat, scene);
  const auto s = dynamics::power_iteration_step(m, kinds, mat, scene);
  expect_within_tolerance(s, exact);
  EXPECT_LE(s.dt, exact * (1 + 1e-12));  // an isolated top eigenvalue (the sliver's): from below
  EXPECT_GT(s.dt / dynamics::critical_time_step(m, kPaper).dt, 10.0);
}

TEST(SpectralStep, EverythingConstrainedIsANumericalError) {
  const auto m = cuboid(1, 1, 1, 0.01, 0.01, 0.01);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  dynamics::Scene scene;
  dynamics::DisplacementConstraint c;
  c.nodes.resize(m.num_nodes());
  for (int i = 0; i < m.num_nodes(); ++i) c.nodes[i] = i;
  scene.constraints = {c};
  EXPECT_THROW(dynamics::power_iteration_step(m, std::vector<ElementKind>(m.num_tets(), ElementKind::tled), mat, scene),
               NumericalError);
}

// dhd_sim's solver.critical_step "power_iteration": the automatic step is safety × 2/ω_max.
TEST(SpectralStep, TheSceneChoosesItsStepFromPowerIterationWhenAsked) {
  auto m = std::make_shared<const mesh::TetMesh>(with_sliver(cuboid(4, 4, 3, 0.04, 0.04, 0.03), 0.99));
  hybrid::DhdConfig c;
  c.material = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  c.scene = bottom_fixed(*m);
  c.explicit_solver.steps = 20;
  const hybrid::DhdScene altitude(m, c);
  EXPECT_FALSE(altitude.spectral_step());
  EXPECT_DOUBLE_EQ(altitude.step_choice().dt, 0.9 * altitude.critical_step().dt);
  c.explicit_solver.critical_step = hybrid::CriticalStepMethod::power_iteration;
  hybrid::DhdScene spectral(m, c);
  ASSERT_TRUE(spectral.spectral_step());
  EXPECT_DOUBLE_EQ(spectral.step_choice().dt, 0.9 * spectral.spectral_step()->dt);
  EXPECT_GT(spectral.step_choice().dt, 5 * altitude.step_choice().dt);
  spectral.step(20);  // and it runs: no energy growth, nothing inverted
  for (int q = 0; q < 3 * m->num_nodes(); ++q) ASSERT_TRUE(std::isfinite(spectral.displacement()[q]));
}
