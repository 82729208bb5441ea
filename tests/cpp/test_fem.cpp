// Element formulations as physics: shape gradients reproduce linear fields, the fast kernels
// equal the reference element functions for every kind and neo-Hookean form, patch tests
// (a homogeneous deformation imposed on the boundary is reproduced exactly inside), a rigid
// 90° rotation is force-free for TLED and corotational but not for linear elements, TLED and
// linear agree to first order at small load, and the assembled tangent is the derivative of
// the assembled force, its columns taking the one-shot stress increment bit for bit (all of
// these for the Mooney–Rivlin law too, through the generic kernel); the output stress and strain
// of every kind under uniaxial stress, rigid rotation and dilation.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "softsim/dynamics/static_solver.hpp"
#include "softsim/fem/assembly.hpp"
#include "softsim/fem/cube_root.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/fem/element_stress.hpp"
#include "softsim/material/uniaxial.hpp"
#include "softsim/mesh/cuboid.hpp"

#include "support/fields.hpp"
#include "support/scenes.hpp"

using namespace softsim;
using fem::ElementKind;

namespace {

using test_scenes::affine_boundary_scene;
using test_scenes::affine_field;
using test_scenes::constraint;
using test_scenes::cuboid;
using test_scenes::gathered_forces;
using test_scenes::interior_nodes;
using test_scenes::kPaper;
using test_scenes::max_abs;

// An element formulation and the law it runs: a neo-Hookean form, or (mooney_rivlin) the
// Mooney–Rivlin law with the same small-strain μ and K split between C10 and C01, or (ogden) a
// three-term Ogden law with that μ = ½ Σ μ_p α_p and K.
struct KindForm {
  ElementKind kind;
  material::NeoHookeanForm form;
  bool mooney_rivlin = false;
  bool ogden = false;
};
fem::Material material_of(const KindForm& kf) {
  const double mu = material::lame_parameters(kPaper).mu;
  if (kf.ogden) {
    const material::Ogden law{3, {1.2 * mu, 0.02 * mu, -0.04 * mu}, {1.5, 6.0, -2.0}, material::bulk_modulus(kPaper)};
    return fem::Material::make(material::small_strain_parameters(law, kPaper.density), law);
  }
  if (!kf.mooney_rivlin) return fem::Material::make(kPaper, kf.form);
  const material::MooneyRivlin law{0.3 * mu, 0.2 * mu, material::bulk_modulus(kPaper)};
  return fem::Material::make(material::small_strain_parameters(law, kPaper.density), law);
}
std::string name_of(const KindForm& kf) {
  const bool finite_strain = kf.kind == ElementKind::tled || kf.kind == ElementKind::anp;
  return std::string(fem::kind_name(kf.kind)) +
         (!finite_strain  ? std::string()
          : kf.ogden       ? "_ogden"
          : kf.mooney_rivlin ? "_mooney_rivlin"
                             : "_" + material::form_name(kf.form));
}
const std::vector<KindForm> kAllKinds = {{ElementKind::linear, material::NeoHookeanForm::paper},
                                         {ElementKind::tled, material::NeoHookeanForm::paper},
                                         {ElementKind::tled, material::NeoHookeanForm::decoupled},
                                         {ElementKind::corotational, material::NeoHookeanForm::paper},
                                         {ElementKind::anp, material::NeoHookeanForm::paper},
                                         {ElementKind::anp, material::NeoHookeanForm::decoupled}};
// The second law behind the same interface: the generic kernel, assembly and tangent.
const std::vector<KindForm> kMooneyRivlinKinds = {{ElementKind::tled, material::NeoHookeanForm::decoupled, true},
                                                  {ElementKind::anp, material::NeoHookeanForm::decoupled, true}};
// The third, written in principal stretches (an eigen-decomposition per element).
const std::vector<KindForm> kOgdenKinds = {{ElementKind::tled, material::NeoHookeanForm::decoupled, false, true},
                                           {ElementKind::anp, material::NeoHookeanForm::decoupled, false, true}};

// A homogeneous deformation with stretch, shear and a 40° rotation (J ≈ 0.87).
Eigen::Matrix3d general_F() {
  Eigen::Matrix3d U;
  U << 1.10, 0.05, -0.08, 0.05, 0.85, 0.04, -0.08, 0.04, 0.93;
  return Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 2).normalized()).toRotationMatrix() * U;
}

}  // namespace

TEST(TetGeometry, GradientsReproduceLinearFieldsAndVolume) {
  const Eigen::Vector3d x0(0.1, 0.2, 0.3), x1(1.2, 0.1, 0.4), x2(0.3, 1.5, 0.2), x3(0.2, 0.4, 0.9);
  const fem::TetShape s = fem::tet_shape(x0, x1, x2, x3);
  EXPECT_NEAR(s.volume, mesh::signed_volume(x0, x1, x2, x3), 1e-15);  // 000 eq. 1
  EXPECT_LT((s.grad[0] + s.grad[1] + s.grad[2] + s.grad[3]).norm(), 1e-12);
  // Σ_a X_a ⊗ ∇N_a = I: the gradient of the identity field.
  const Eigen::Matrix3d I = x0 * s.grad[0].transpose() + x1 * s.grad[1].transpose() + x2 * s.grad[2].transpose() +
                            x3 * s.grad[3].transpose();
  EXPECT_LT((I - Eigen::Matrix3d::Identity()).norm(), 1e-12);
}

TEST(CubeRoot, NewtonRootIsExactOnItsRange) {
  for (double J = fem::kInvCbrtMinJ; J <= fem::kInvCbrtMaxJ; J *= 1.01) {
    const double exact = 1.0 / std::cbrt(J);
    EXPECT_NEAR(fem::inv_cbrt_newton(J), exact, 1e-15 * exact) << "J = " << J;
  }
}

// The law's dP(F)[dF] in one call: the neo-Hookean one-shot function, or the law's own
// linearisation for a law that has no one-shot form.
Eigen::Matrix3d one_shot_increment(const material::HyperelasticLaw& law, const Eigen::Matrix3d& F,
                                   const Eigen::Matrix3d& dF) {
  if (const auto* nh = std::get_if<material::NeoHookean>(&law)) return material::first_piola_increment(*nh, F, dF);
  return material::first_piola_increment(law, material::linearise(law, F), dF);
}

class Kinds : public ::testing::TestWithParam<KindForm> {};

TEST_P(Kinds, FastKernelsEqualTheReferenceElementForces) {
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);
  const fem::Material mat = material_of(GetParam());
  const std::vector<ElementKind> kinds(m.num_tets(), GetParam().kind);
  fem::ElementSet set(m, kinds, mat);
  const fem::Assembler ref(m, kinds, mat);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-0.002, 0.002);
  std::vector<double> u = affine_field(m, general_F());
  for (double& x : u) x += d(rng);
  const std::vector<double> f = gathered_forces(set, u);
  Eigen::VectorXd fr;
  ref.internal_forces(u.data(), fr);
  const double scale = fr.lpNorm<Eigen::Infinity>();
  ASSERT_GT(scale, 0);
  for (std::size_t q = 0; q < f.size(); ++q) EXPECT_NEAR(f[q], fr[q], 1e-12 * scale) << "dof " << q;
}

TEST_P(Kinds, ForcePatchTestAffineFieldLeavesInteriorNodesInEquilibrium) {
  // A homogeneous deformation gives a uniform stress; interior nodes then receive balancing
  // contributions from their elements (000 eq. 23 sums to zero).
  const auto m = cuboid(4, 3, 3, 0.04, 0.03, 0.03);
  const fem::Material mat = material_of(GetParam());
  fem::ElementSet set(m, std::vector<ElementKind>(m.num_tets(), GetParam().kind), mat);
  const std::vector<double> f = gathered_forces(set, affine_field(m, general_F()));
  const double fmax = max_abs(f);
  ASSERT_GT(fmax, 0);
  for (int i : interior_nodes(m))
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[3 * i + k], 0.0, 1e-12 * fmax) << "node " << i;
}

TEST_P(Kinds, PatchTestHomogeneousDeformationReproducedInside) {
  // Boundary nodes prescribed to X ↦ F X; the static solve must put every interior node on the
  // same affine map.
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  const fem::Material mat = material_of(GetParam());
  const Eigen::Matrix3d F = general_F();
  dynamics::StaticOptions opt;
  opt.increments = 4;
  opt.tolerance = 1e-12;
  const auto r = dynamics::solve_static(m, std::vector<ElementKind>(m.num_tets(), GetParam().kind), mat,
                                        affine_boundary_scene(m, F), opt);
  const auto expected = affine_field(m, F);
  const auto inside = interior_nodes(m);
  ASSERT_FALSE(inside.empty());
  for (int i : inside)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.displacement[3 * i + k], expected[3 * i + k], 1e-10 * 0.03) << "node " << i;
}

TEST_P(Kinds, AssembledTangentIsTheDerivativeOfTheAssembledForce) {
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  const fem::Material mat = material_of(GetParam());
  const fem::Assembler as(m, std::vector<ElementKind>(m.num_tets(), GetParam().kind), mat);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-0.001, 0.001);
  std::vector<double> u = affine_field(m, general_F());
  for (double& x : u) x += d(rng);
  Eigen::SparseMatrix<double> K = as.pattern();
  as.tangent(u.data(), K);
  const Eigen::MatrixXd Kd = Eigen::MatrixXd(K);
  Eigen::VectorXd v(u.size());
  for (auto& x : v) x = d(rng);
  const double h = 1e-4;
  std::vector<double> up = u, um = u;
  for (std::size_t q = 0; q < u.size(); ++q) up[q] += h * v[q], um[q] -= h * v[q];
  Eigen::VectorXd fp, fm;
  as.internal_forces(up.data(), fp);
  as.internal_forces(um.data(), fm);
  const Eigen::VectorXd fd = (fp - fm) / (2 * h);
  EXPECT_LT((Kd * v - fd).norm(), 1e-6 * fd.norm());
}

TEST_P(Kinds, TangentColumnsTakeTheOneShotIncrementBitForBit) {
  // The element tangent does the set-up that depends on F alone once for its 12 columns; every
  // column's dP must still be exactly the one-shot increment's.
  const fem::Material mat = material_of(GetParam());
  const ElementKind kind = GetParam().kind;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-0.2, 0.2);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::Matrix3d F = general_F(), dF;
    for (int i = 0; i < 9; ++i) F(i / 3, i % 3) += 0.1 * d(rng), dF(i / 3, i % 3) = d(rng);
    Eigen::Matrix3d one_shot;
    switch (kind) {
      case ElementKind::linear: one_shot = material::linear_stress_increment(mat.lame, dF); break;
      case ElementKind::tled: one_shot = one_shot_increment(mat.law, F, dF); break;
      case ElementKind::corotational: one_shot = material::corotated_first_piola_increment(mat.lame, F, dF); break;
      case ElementKind::anp: one_shot = one_shot_increment(mat.isochoric, F, dF); break;
    }
    const Eigen::Matrix3d dP = fem::FirstPiolaLinearisation(mat, kind, F).increment(dF);
    for (int i = 0; i < 9; ++i) EXPECT_EQ(dP(i / 3, i % 3), one_shot(i / 3, i % 3)) << "trial " << trial << ", entry " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(AllKinds, Kinds, ::testing::ValuesIn(kAllKinds),
                         [](const auto& info) { return name_of(info.param); });
INSTANTIATE_TEST_SUITE_P(MooneyRivlin, Kinds, ::testing::ValuesIn(kMooneyRivlinKinds),
                         [](const auto& info) { return name_of(info.param); });
INSTANTIATE_TEST_SUITE_P(Ogden, Kinds, ::testing::ValuesIn(kOgdenKinds),
                         [](const auto& info) { return name_of(info.param); });

TEST(ElementSet, MooneyRivlinWithoutC01EqualsTheDecoupledNeoHookeanKernelsToRoundOff) {
  // The generic kernel with C01 = 0 against the hand-written decoupled neo-Hookean kernels, for
  // TLED and ANP elements side by side.
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);
  std::vector<ElementKind> kinds(m.num_tets(), ElementKind::tled);
  for (int e = 0; e < m.num_tets(); e += 2) kinds[e] = ElementKind::anp;
  const fem::Material nh = fem::Material::make(kPaper, material::NeoHookeanForm::decoupled);
  const auto& law = std::get<material::NeoHookean>(nh.law);
  const material::MooneyRivlin mr_law{law.c10(), 0.0, law.bulk};
  const fem::Material mr = fem::Material::make(kPaper, mr_law);
  fem::ElementSet a(m, kinds, nh), b(m, kinds, mr);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> d(-0.002, 0.002);
  std::vector<double> u = affine_field(m, general_F());
  for (double& x : u) x += d(rng);
  const std::vector<double> fa = gathered_forces(a, u), fb = gathered_forces(b, u);
  const double scale = max_abs(fa);
  ASSERT_GT(scale, 0);
  for (std::size_t q = 0; q < fa.size(); ++q) EXPECT_NEAR(fb[q], fa[q], 1e-13 * scale) << "dof " << q;
}

TEST(ElementSet, OgdenWithAlphaPlusMinusTwoEqualsTheMooneyRivlinKernelsToRoundOff) {
  // α = (2, −2), μ = (2 C10, −2 C01): the eigen-decomposition kernel against the invariant one,
  // for TLED and ANP elements side by side.
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);
  std::vector<ElementKind> kinds(m.num_tets(), ElementKind::tled);
  for (int e = 0; e < m.num_tets(); e += 2) kinds[e] = ElementKind::anp;
  const double mu = material::lame_parameters(kPaper).mu;
  const material::MooneyRivlin mr_law{0.3 * mu, 0.2 * mu, material::bulk_modulus(kPaper)};
  const material::Ogden og_law{2, {2.0 * mr_law.c10, -2.0 * mr_law.c01}, {2.0, -2.0}, mr_law.bulk};
  fem::ElementSet a(m, kinds, fem::Material::make(kPaper, mr_law)), b(m, kinds, fem::Material::make(kPaper, og_law));
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> d(-0.002, 0.002);
  std::vector<double> u = affine_field(m, general_F());
  for (double& x : u) x += d(rng);
  const std::vector<double> fa = gathered_forces(a, u), fb = gathered_forces(b, u);
  const double scale = max_abs(fa);
  ASSERT_GT(scale, 0);
  for (std::size_t q = 0; q < fa.size(); ++q) EXPECT_NEAR(fb[q], fa[q], 1e-12 * scale) << "dof " << q;
}

TEST(RigidRotation, NinetyDegreesIsForceFreeForTledCorotationalAndAnpButNotLinear) {
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d(0, 0, 1)).toRotationMatrix();
  const std::vector<double> u = affine_field(m, R);
  const double force_scale = kPaper.youngs_modulus * 0.01 * 0.01;  // E h²
  for (const KindForm& kf : kAllKinds) {
    fem::ElementSet set(m, std::vector<ElementKind>(m.num_tets(), kf.kind), fem::Material::make(kPaper, kf.form));
    const double fmax = max_abs(gathered_forces(set, u));
    if (kf.kind == ElementKind::linear)
      EXPECT_GT(fmax, 0.1 * force_scale) << "small-strain elements must see the rotation as strain";
    else
      EXPECT_LT(fmax, 1e-11 * force_scale) << name_of(kf);
  }
}

TEST(SmallLoad, TledAndLinearAgreeToFirstOrder) {
  // Static: bottom clamped, a small downward push of the top face. The relative difference of
  // the TLED and linear solutions must shrink in proportion to the load.
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  std::vector<double> ratio;
  for (double s : {1e-3, 1e-4}) {
    dynamics::Scene scene;
    dynamics::DisplacementConstraint top;
    top.nodes = m.node_sets.at("top");
    top.displacement = Eigen::Vector3d(0.2 * s * 0.03, 0.1 * s * 0.03, -s * 0.03);
    scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero()), top};
    dynamics::StaticOptions opt;
    opt.increments = 1;
    opt.tolerance = 1e-10;
    const auto tl = dynamics::solve_static(m, std::vector<ElementKind>(m.num_tets(), ElementKind::tled), mat, scene, opt);
    const auto li = dynamics::solve_static(m, std::vector<ElementKind>(m.num_tets(), ElementKind::linear), mat, scene, opt);
    double diff = 0, norm = 0;
    for (std::size_t q = 0; q < tl.displacement.size(); ++q) {
      diff += std::pow(tl.displacement[q] - li.displacement[q], 2);
      norm += std::pow(li.displacement[q], 2);
    }
    ratio.push_back(std::sqrt(diff / norm));
  }
  EXPECT_LT(ratio[0], 1e-2);
  EXPECT_GT(ratio[0], 0.0);
  EXPECT_NEAR(ratio[1] / ratio[0], 0.1, 0.02);  // first order in the load
}

TEST(ElementSet, GroupsArePaddedAndCountsKept) {
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);  // 90 elements
  std::vector<ElementKind> kinds(m.num_tets(), ElementKind::tled);
  for (int e = 0; e < 13; ++e) kinds[e * 3] = ElementKind::linear;
  kinds[1] = ElementKind::corotational;
  fem::ElementSet set(m, kinds, fem::Material::make(kPaper, material::NeoHookeanForm::paper));
  EXPECT_EQ(set.count(ElementKind::linear), 13);
  EXPECT_EQ(set.count(ElementKind::corotational), 1);
  EXPECT_EQ(set.count(ElementKind::tled), 90 - 14);
  for (const auto& g : set.groups()) {
    EXPECT_EQ(g.begin % fem::kBlock, 0);
    EXPECT_EQ(g.end % fem::kBlock, 0);
  }
  const auto ranges = set.balanced_ranges(3);
  for (int r : ranges) EXPECT_EQ(r % fem::kBlock, 0);
  EXPECT_EQ(ranges.back(), set.padded_size());
}

TEST(ElementSet, CorotationalKernelIsExactForNearlyCollapsedAndStronglyStretchedElements) {
  // Far outside the range of the vectorised polar iteration (a block squashed to 1e-9 of its
  // height, or stretched 40-fold, and rotated): the element must take the exact path and give
  // finite forces equal to the reference, never NaN.
  const auto m = cuboid(1, 1, 1, 0.01, 0.01, 0.01);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  const std::vector<ElementKind> kinds(m.num_tets(), ElementKind::corotational);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  for (double squash : {1e-3, 1e-6, 1e-9, 40.0}) {
    Eigen::Matrix3d U = Eigen::Matrix3d::Identity();
    U(2, 2) = squash;
    U(0, 2) = 0.3;
    fem::ElementSet set(m, kinds, mat);
    const fem::Assembler ref(m, kinds, mat);
    const std::vector<double> u = affine_field(m, R * U);
    const std::vector<double> f = gathered_forces(set, u);
    Eigen::VectorXd fr;
    ref.internal_forces(u.data(), fr);
    ASSERT_TRUE(fr.allFinite());
    for (std::size_t q = 0; q < f.size(); ++q)
      EXPECT_NEAR(f[q], fr[q], 1e-10 * fr.lpNorm<Eigen::Infinity>()) << "squash " << squash << ", dof " << q;
  }
}

TEST(ElementSet, DecoupledKernelIsExactOutsideTheNewtonRootRange) {
  // Strong dilatation (J ≈ 11) and compression (J ≈ 0.09) take the library-root path.
  const auto m = cuboid(1, 1, 1, 0.01, 0.01, 0.01);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::decoupled);
  const std::vector<ElementKind> kinds(m.num_tets(), ElementKind::tled);
  for (double s : {2.2, 0.45}) {
    fem::ElementSet set(m, kinds, mat);
    const fem::Assembler ref(m, kinds, mat);
    const std::vector<double> u = affine_field(m, s * Eigen::Matrix3d::Identity());
    const std::vector<double> f = gathered_forces(set, u);
    Eigen::VectorXd fr;
    ref.internal_forces(u.data(), fr);
    for (std::size_t q = 0; q < f.size(); ++q) EXPECT_NEAR(f[q], fr[q], 1e-12 * fr.lpNorm<Eigen::Infinity>());
  }
}

TEST(ElementSet, TiledSweepUpdatesEachNodeOnceAfterAllItsElements) {
  const auto m = cuboid(5, 4, 3, 0.05, 0.04, 0.03);
  std::vector<ElementKind> kinds(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) kinds[e] = static_cast<ElementKind>((3 * e + e / 7) % 3);
  test_scenes::expect_tiled_sweep_equals_whole_pass(
      m, kinds, fem::Material::make(kPaper, material::NeoHookeanForm::paper), affine_field(m, general_F()));
}

// ---- Element stress and strain for output (fem/element_stress.hpp).

namespace {

// Uniaxial stress along z by the stretch a: F = diag(t, t, a) with the lateral stretch t that
// frees the lateral faces, and the axial Cauchy stress, from material/uniaxial.hpp (each law's
// energy, written independently of the stress code). Linear elements report the small-strain
// stress, which is the nominal one E (a − 1); the others σ₃₃ = P₃₃ a / J = P₃₃ / t². The
// corotational law's P is the linear one for a diagonal stretch, so it shares the linear t.
struct Uniaxial {
  Eigen::Matrix3d F;
  double sigma = 0;
};
Uniaxial uniaxial(const KindForm& kf, const fem::Material& m, double a) {
  const bool neo_hookean = kf.kind == ElementKind::tled || kf.kind == ElementKind::anp;
  const material::UniaxialSolution s =
      neo_hookean ? material::uniaxial_neo_hookean(std::get<material::NeoHookean>(m.law), a)
                  : material::uniaxial_linear(kPaper, a);
  Uniaxial u;
  u.F = Eigen::Vector3d(s.lateral_stretch, s.lateral_stretch, a).asDiagonal();
  u.sigma = kf.kind == ElementKind::linear ? s.nominal_stress
                                           : s.nominal_stress / (s.lateral_stretch * s.lateral_stretch);
  return u;
}

std::vector<ElementKind> all_of(const mesh::TetMesh& m, ElementKind kind) {
  return std::vector<ElementKind>(m.num_tets(), kind);
}

}  // namespace

TEST(ElementStress, UniaxialStretchGivesTheAnalyticStressInEveryElementOfEveryKind) {
  const auto m = cuboid(2, 2, 3, 0.02, 0.02, 0.03);
  const double E = kPaper.youngs_modulus;
  for (const KindForm& kf : kAllKinds)
    for (const double a : {1.2, 0.8}) {
      const fem::Material mat = fem::Material::make(kPaper, kf.form);
      const Uniaxial ua = uniaxial(kf, mat, a);
      fem::ElementStress out(m, all_of(m, kf.kind), mat);
      out.evaluate(affine_field(m, ua.F).data());
      const Eigen::Matrix3d sigma = Eigen::Vector3d(0, 0, ua.sigma).asDiagonal();
      const Eigen::Matrix3d strain = 0.5 * (ua.F * ua.F - Eigen::Matrix3d::Identity());
      ASSERT_GT(std::fabs(ua.sigma), 0.05 * E);
      for (int e = 0; e < m.num_tets(); ++e) {
        EXPECT_LT((out.stress()[e] - sigma).cwiseAbs().maxCoeff(), 1e-9 * E) << name_of(kf) << " a=" << a << " e=" << e;
        EXPECT_LT((out.strain()[e] - strain).cwiseAbs().maxCoeff(), 1e-14) << name_of(kf) << " e=" << e;
        EXPECT_NEAR(out.von_mises()[e], std::fabs(ua.sigma), 1e-9 * E) << name_of(kf) << " e=" << e;
      }
    }
}

TEST(ElementStress, RigidRotationIsStressFreeForTledCorotationalAndAnpButNotLinear) {
  // A rotation alone (40° about a skew axis): zero stress and strain for the objective laws,
  // and for a rotated uniaxial stretch Q F the stress rotated with it, Q σ(F) Qᵀ. Linear
  // elements take the rotation for strain.
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  const double E = kPaper.youngs_modulus;
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const KindForm& kf : kAllKinds) {
    const fem::Material mat = fem::Material::make(kPaper, kf.form);
    fem::ElementStress out(m, all_of(m, kf.kind), mat);
    out.evaluate(affine_field(m, Q).data());
    double largest = 0;
    for (int e = 0; e < m.num_tets(); ++e) {
      largest = std::max(largest, out.stress()[e].cwiseAbs().maxCoeff());
      EXPECT_LT(out.strain()[e].cwiseAbs().maxCoeff(), 1e-14) << name_of(kf);
    }
    if (kf.kind == ElementKind::linear) {
      EXPECT_GT(largest, 0.1 * E) << "small-strain elements must see the rotation as strain";
      continue;
    }
    EXPECT_LT(largest, 1e-11 * E) << name_of(kf);
    const Uniaxial ua = uniaxial(kf, mat, 1.2);
    out.evaluate(affine_field(m, Q * ua.F).data());
    const Eigen::Matrix3d rotated = Q * Eigen::Vector3d(0, 0, ua.sigma).asDiagonal() * Q.transpose();
    for (int e = 0; e < m.num_tets(); ++e)
      EXPECT_LT((out.stress()[e] - rotated).cwiseAbs().maxCoeff(), 1e-9 * E) << name_of(kf) << " e=" << e;
  }
}

TEST(ElementStress, VonMisesVanishesForHydrostaticStateAndMeasuresShear) {
  EXPECT_EQ(fem::von_mises_stress(-250.0 * Eigen::Matrix3d::Identity()), 0.0);
  Eigen::Matrix3d shear = Eigen::Matrix3d::Zero();
  shear(0, 1) = shear(1, 0) = 100.0;
  EXPECT_NEAR(fem::von_mises_stress(shear), std::sqrt(3.0) * 100.0, 1e-12);  // σ_vM = √3 τ
  // A uniform dilation loads every kind hydrostatically: a pressure, no equivalent stress.
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  for (const KindForm& kf : kAllKinds) {
    fem::ElementStress out(m, all_of(m, kf.kind), fem::Material::make(kPaper, kf.form));
    out.evaluate(affine_field(m, 1.1 * Eigen::Matrix3d::Identity()).data());
    for (int e = 0; e < m.num_tets(); ++e) {
      const double pressure = out.stress()[e].trace() / 3.0;
      EXPECT_GT(pressure, 0.01 * kPaper.youngs_modulus) << name_of(kf);
      EXPECT_LT(out.von_mises()[e], 1e-12 * pressure) << name_of(kf);
    }
  }
}
