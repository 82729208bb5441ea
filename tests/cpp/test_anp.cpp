// The average-nodal-pressure tetrahedron (fem/nodal_pressure.hpp; Bonet & Burton 1998) as
// physics: under a homogeneous deformation it is exactly TLED; its forces are the gradient of
// its energy (isochoric per element, volumetric per node) and the assembled tangent their
// derivative, in a mixed mesh too; the explicit engine's vectorised path equals the reference
// assembly and its energy; undamped explicit runs conserve energy, damped ones settle on the
// static solution, bit-identically on 1 and 2 threads; and it does not lock: the tip deflection
// of a cantilever stays put as ν → 0.5 while linear tets stiffen without bound.
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

// ANP in the middle layers, the other kinds around it: interfaces of every pair.
std::vector<ElementKind> mixed_kinds(const mesh::TetMesh& m) {
  std::vector<ElementKind> kinds(m.num_tets());
  const auto& layer = m.element_tags.at("layer");
  for (int e = 0; e < m.num_tets(); ++e)
    kinds[e] = layer[e] == 0 ? ElementKind::linear : layer[e] == 3 ? ElementKind::tled
               : e % 9 == 0  ? ElementKind::corotational
                             : ElementKind::anp;
  return kinds;
}

class Forms : public ::testing::TestWithParam<NeoHookeanForm> {};

}  // namespace

TEST_P(Forms, HomogeneousDeformationMakesAnpExactlyTled) {
  // Every nodal J_a is a weighted mean of equal element J's, so p̄ = U'(J) everywhere, boundary
  // nodes included.
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);
  const fem::Material mat = fem::Material::make(kPaper, GetParam());
  fem::ElementSet anp(m, std::vector<ElementKind>(m.num_tets(), ElementKind::anp), mat);
  fem::ElementSet tled(m, std::vector<ElementKind>(m.num_tets(), ElementKind::tled), mat);
  Eigen::Matrix3d F;
  F << 0.8, 0.1, 0.0, -0.05, 1.1, 0.07, 0.02, 0.0, 0.9;
  const auto u = affine_field(m, F);
  const auto fa = gathered_forces(anp, u), ft = gathered_forces(tled, u);
  const double scale = max_abs(ft);
  ASSERT_GT(scale, 0);
  for (std::size_t q = 0; q < fa.size(); ++q) EXPECT_NEAR(fa[q], ft[q], 1e-12 * scale) << "dof " << q;
  const fem::Assembler as_anp(m, std::vector<ElementKind>(m.num_tets(), ElementKind::anp), mat);
  const fem::Assembler as_tled(m, std::vector<ElementKind>(m.num_tets(), ElementKind::tled), mat);
  EXPECT_NEAR(as_anp.strain_energy(u.data()), as_tled.strain_energy(u.data()), 1e-12 * as_tled.strain_energy(u.data()));
}

TEST_P(Forms, ForcesAreTheGradientOfTheEnergyAndTheTangentTheirDerivative) {
  const auto m = cuboid(3, 3, 4, 0.03, 0.03, 0.04);
  const fem::Material mat = fem::Material::make(kPaper, GetParam());
  const fem::Assembler as(m, mixed_kinds(m), mat);
  const std::vector<double> u = rough_field(m, 7, 0.0008);
  expect_forces_are_the_energy_gradient_and_the_tangent_their_derivative(as, u);
}

TEST_P(Forms, ExplicitPathEqualsTheReferenceAssemblyInAMixedMesh) {
  const auto m = cuboid(4, 3, 4, 0.04, 0.03, 0.04);
  const fem::Material mat = fem::Material::make(kPaper, GetParam());
  const auto kinds = mixed_kinds(m);
  fem::ElementSet set(m, kinds, mat, 16);
  const fem::Assembler as(m, kinds, mat);
  const std::vector<double> u = rough_field(m, 5, 0.001);
  const auto f = gathered_forces(set, u);
  Eigen::VectorXd fr;
  as.internal_forces(u.data(), fr);
  const double scale = fr.lpNorm<Eigen::Infinity>();
  for (std::size_t q = 0; q < f.size(); ++q) EXPECT_NEAR(f[q], fr[q], 1e-11 * scale) << "dof " << q;
  // Energy: per-element (isochoric) part plus the nodal volumetric part.
  std::vector<double> energy(set.padded_size()), volume_ratio(set.padded_size());
  double min_j = 1e300;
  int min_e = -1;
  set.energies(u.data(), 0, set.padded_size(), energy.data(), volume_ratio.data(), min_j, min_e);
  double w = set.nodal_volumetric_energy(volume_ratio.data());
  for (double x : energy) w += x;
  EXPECT_NEAR(w, as.strain_energy(u.data()), 1e-12 * w);
}

INSTANTIATE_TEST_SUITE_P(BothForms, Forms, ::testing::Values(NeoHookeanForm::paper, NeoHookeanForm::decoupled),
                         [](const auto& info) { return material::form_name(info.param); });

TEST(AnpExplicit, UndampedFreeVibrationConservesEnergy) {
  // As for TLED (test_dynamics): released from the static shape of a 5 % shear, near-incompressible.
  const auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  const material::ElasticParameters soft{5000.0, 0.49, 1000.0};
  test_scenes::expect_free_vibration_conserves_energy(m, std::vector<ElementKind>(m.num_tets(), ElementKind::anp),
                                                      fem::Material::make(soft, NeoHookeanForm::decoupled));
}

TEST(AnpExplicit, DampedRunSettlesOnTheStaticSolutionBitIdenticallyOnOneAndTwoThreads) {
  const auto m = cuboid(4, 3, 4, 0.04, 0.03, 0.04);
  const fem::Material mat = fem::Material::make(kPaper, NeoHookeanForm::paper);
  const auto kinds = mixed_kinds(m);
  auto [scene, opt] = test_scenes::damped_sheared_press(m);
  std::vector<std::vector<double>> results;
  for (int threads : {1, 2}) {
    opt.threads = threads;
    // Small tiles: the threads share the sweep.
    results.push_back(run_explicit(m, kinds, mat, scene, opt, {}, 16).displacement);
  }
  ASSERT_EQ(results[0].size(), results[1].size());
  EXPECT_EQ(0, std::memcmp(results[0].data(), results[1].data(), results[0].size() * sizeof(double)));
  const auto stat = dynamics::solve_static(m, kinds, mat, scene, {});
  const double diff = max_abs_diff(results[0], stat.displacement);
  EXPECT_LT(diff, 1e-9 * max_abs(stat.displacement));
}

namespace {

// Block 6 × 6 × 3 cm of 6 × 6 × 3 cells, bottom clamped, a small downward force (0.1 mN, depth
// 1e-5 of the height: geometric nonlinearity plays no part) shared by the top nodes within 1 cm
// of the centre — a blunt probe: their mean vertical displacement (static).
double indentation_depth(ElementKind kind, double nu) {
  static const auto m = cuboid(6, 6, 3, 0.06, 0.06, 0.03);
  std::vector<int> patch;
  for (int i : m.node_sets.at("top"))
    if ((m.nodes[i] - Eigen::Vector3d(0.03, 0.03, 0.03)).norm() <= 0.0101) patch.push_back(i);
  const material::ElasticParameters p{5000.0, nu, 1000.0};
  const fem::Material mat = fem::Material::make(p, NeoHookeanForm::decoupled);
  dynamics::Scene scene;
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero())};
  dynamics::NodalLoad load;
  load.name = "probe";
  load.nodes = patch;
  load.force_per_node = Eigen::Vector3d(0, 0, -1e-4 / patch.size());
  scene.loads = {load};
  dynamics::StaticOptions opt;
  opt.increments = 1;
  opt.tolerance = 1e-7;  // the residual's round-off floor grows with λ/μ (5000 at ν = 0.4999)
  const auto r = dynamics::solve_static(m, std::vector<ElementKind>(m.num_tets(), kind), mat, scene, opt);
  double sum = 0;
  for (int i : patch) sum += r.displacement[3 * i + 2];
  return -sum / patch.size();
}

}  // namespace

TEST(AnpLocking, IndentationDepthStaysFiniteAsPoissonRatioApproachesOneHalf) {
  // Volumetric locking: as ν → 0.5 a locking element's response goes to zero with 1 − 2ν; a
  // locking-free one converges to the incompressible value. From ν = 0.499 to 0.4999, 1 − 2ν
  // falls tenfold.
  const double tet_499 = indentation_depth(ElementKind::tled, 0.499);
  const double tet_4999 = indentation_depth(ElementKind::tled, 0.4999);
  const double anp_499 = indentation_depth(ElementKind::anp, 0.499);
  const double anp_4999 = indentation_depth(ElementKind::anp, 0.4999);
  ASSERT_GT(tet_4999, 0.0);
  EXPECT_LT(tet_4999 / tet_499, 0.4) << "constant-strain tets must lock";
  EXPECT_GT(anp_4999 / anp_499, 0.85) << "ANP must not lock";
  EXPECT_GT(anp_4999 / tet_4999, 5.0);
}
