// The stable neo-Hookean law (Smith, de Goes, Kim 2018) as physics: stress as the energy
// gradient, its tangent, objectivity, the small-strain limit that makes (E, ν) mean the same
// material as for every other element, an analytic homogeneous deformation, and what the law is
// for: a finite energy and a restoring stress at J ≤ 0, so that an inverted element is pushed
// back out by the explicit engine instead of ending the run.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/dynamics/stable_step.hpp"
#include "softsim/fem/assembly.hpp"
#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/material/hyperelastic.hpp"
#include "softsim/material/small_strain.hpp"
#include "softsim/material/stable_neo_hookean.hpp"

#include "support/scenes.hpp"

#include <limits>

using namespace softsim;
using namespace softsim::material;

namespace {

using test_scenes::kPaper;

const StableNeoHookean kLaw = StableNeoHookean::from(kPaper);

Eigen::Matrix3d random_F(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> d(-amplitude, amplitude);
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) F(i, j) += d(rng);
  return F;
}

// Deformation gradients of both orientations: moderate ones, a reflection (J = −1), a flat
// one (J = 0) and strongly inverted ones.
std::vector<Eigen::Matrix3d> test_gradients() {
  std::mt19937 rng(11);
  std::vector<Eigen::Matrix3d> Fs;
  for (int k = 0; k < 4; ++k) Fs.push_back(random_F(rng, 0.3));
  Fs.push_back(Eigen::Vector3d(-1, 1, 1).asDiagonal());
  Fs.push_back(Eigen::Vector3d(1.2, 0.9, 0.0).asDiagonal());
  for (int k = 0; k < 3; ++k) {
    Eigen::Matrix3d F = random_F(rng, 0.4);
    F.col(2) *= -1.5;  // mirrored: J < 0
    Fs.push_back(F);
  }
  return Fs;
}

}  // namespace

TEST(StableNeoHookean, StressFreeAndEnergyFreeAtRest) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_NEAR(strain_energy_density(kLaw, I), 0.0, 1e-12 * kLaw.mu);
  EXPECT_LT(first_piola(kLaw, I).norm(), 1e-12 * kLaw.mu);
  EXPECT_LT(second_piola(kLaw, I).norm(), 1e-12 * kLaw.mu);
}

// The same energy as Smith et al.'s W = μ/2 (I_C − 3) + λ/2 (J − α)² − μ/2 ln(I_C + 1) with
// α = 1 + 3μ/(4λ), up to the constant that makes W(I) = 0.
TEST(StableNeoHookean, IsSmithDeGoesKimsEnergyUpToAConstant) {
  const double alpha = 1.0 + 0.75 * kLaw.mu / kLaw.lambda;
  const auto smith = [&](const Eigen::Matrix3d& F) {
    const double Ic = F.squaredNorm(), J = F.determinant();
    return 0.5 * kLaw.mu * (Ic - 3.0) + 0.5 * kLaw.lambda * (J - alpha) * (J - alpha) - 0.5 * kLaw.mu * std::log(Ic + 1.0);
  };
  const double shift = smith(Eigen::Matrix3d::Identity());
  for (const auto& F : test_gradients())
    EXPECT_NEAR(strain_energy_density(kLaw, F), smith(F) - shift, 1e-10 * kLaw.mu);
}

// Simple shear F = I + γ e₁⊗e₂ (J = 1): σ₁₂ = μ γ (γ² + 3)/(γ² + 4), from σ = P Fᵀ / J with
// B₁₂ = γ: the shear stress of the paper's energy written out by hand.
TEST(StableNeoHookean, SimpleShearMatchesTheClosedForm) {
  for (double gamma : {0.01, 0.3, 1.0, 2.5}) {
    Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
    F(0, 1) = gamma;
    const Eigen::Matrix3d sigma = first_piola(kLaw, F) * F.transpose();
    const double expected = kLaw.mu * gamma * (gamma * gamma + 3.0) / (gamma * gamma + 4.0);
    EXPECT_NEAR(sigma(0, 1), expected, 1e-12 * kLaw.mu) << gamma;
    EXPECT_NEAR(sigma(0, 1), sigma(1, 0), 1e-12 * kLaw.mu);  // symmetric Cauchy stress
  }
}

// P = ∂W/∂F by central differences of W, and S = F⁻¹ P from C, at every test gradient (S only
// where J > 0: C does not know the orientation).
TEST(StableNeoHookean, FirstPiolaIsTheEnergyGradientAlsoWhenInverted) {
  const double h = 1e-6;
  for (const auto& F : test_gradients()) {
    const Eigen::Matrix3d P = first_piola(kLaw, F);
    Eigen::Matrix3d fd;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Eigen::Matrix3d Fp = F, Fm = F;
        Fp(i, j) += h;
        Fm(i, j) -= h;
        fd(i, j) = (strain_energy_density(kLaw, Fp) - strain_energy_density(kLaw, Fm)) / (2 * h);
      }
    EXPECT_LT((P - fd).norm(), 1e-6 * kLaw.mu) << F;
    if (F.determinant() > 0.1) EXPECT_LT((F * second_piola(kLaw, F.transpose() * F) - P).norm(), 1e-9 * kLaw.mu);
  }
}

TEST(StableNeoHookean, TangentMatchesFiniteDifferenceOfStressAlsoWhenInverted) {
  const double h = 1e-6;
  std::mt19937 rng(5);
  for (const auto& F : test_gradients()) {
    const auto at = linearise(kLaw, F);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Matrix3d dF = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
      const Eigen::Matrix3d fd = (first_piola(kLaw, F + h * dF) - first_piola(kLaw, F - h * dF)) / (2 * h);
      EXPECT_LT((first_piola_increment(kLaw, at, dF) - fd).norm(), 1e-6 * kLaw.mu * (1 + dF.norm())) << F;
    }
  }
}

TEST(StableNeoHookean, ObjectiveUnderRotation) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  for (const auto& F : test_gradients()) {
    EXPECT_NEAR(strain_energy_density(kLaw, R * F), strain_energy_density(kLaw, F), 1e-10 * kLaw.mu);
    EXPECT_LT((first_piola(kLaw, R * F) - R * first_piola(kLaw, F)).norm(), 1e-10 * kLaw.mu);
  }
  // A rigid rotation alone stores no energy and no stress.
  EXPECT_NEAR(strain_energy_density(kLaw, R), 0.0, 1e-10 * kLaw.mu);
  EXPECT_LT(first_piola(kLaw, R).norm(), 1e-10 * kLaw.mu);
}

// Smith et al.'s reparametrisation: the tangent at F = I is Hooke's law with the (μ, λ) of the
// configured (E, ν), so a small strain means the same material as for the linear element.
TEST(StableNeoHookean, SmallStrainLimitIsLinearElasticityWithTheConfiguredConstants) {
  const LameParameters lame = lame_parameters(kPaper);
  const auto at = linearise(kLaw, Eigen::Matrix3d::Identity());
  std::mt19937 rng(3);
  for (int k = 0; k < 5; ++k) {
    const Eigen::Matrix3d H = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d hooke = linear_stress_increment(lame, H);
    EXPECT_LT((first_piola_increment(kLaw, at, H) - hooke).norm(), 1e-10 * lame.mu * H.norm());
    // and the stress of a small displacement gradient, to first order
    const double eps = 1e-7;
    const Eigen::Matrix3d P = first_piola(kLaw, Eigen::Matrix3d::Identity() + eps * H);
    EXPECT_LT((P / eps - hooke).norm(), 1e-5 * lame.mu * H.norm());
  }
  const ElasticParameters back = small_strain_parameters(kLaw, kPaper.density);
  EXPECT_NEAR(back.youngs_modulus, kPaper.youngs_modulus, 1e-9 * kPaper.youngs_modulus);
  EXPECT_NEAR(back.poisson_ratio, kPaper.poisson_ratio, 1e-12);
}

TEST(StableNeoHookean, IsochoricPartPlusVolumetricTermIsTheWholeLaw) {
  const StableNeoHookean rest = isochoric_part(kLaw);
  const double kappa = volumetric_modulus(kLaw);
  for (const auto& F : test_gradients()) {
    const double J = F.determinant();
    EXPECT_NEAR(strain_energy_density(rest, F) + 0.5 * kappa * (J - 1) * (J - 1), strain_energy_density(kLaw, F),
                1e-10 * kLaw.mu);
    EXPECT_LT((first_piola(rest, F) + kappa * (J - 1) * cofactor(F) - first_piola(kLaw, F)).norm(), 1e-10 * kLaw.mu);
  }
}

// What the law is for: at J ≤ 0 the energy is finite and the stress points back out. The rate
// of J under a velocity −P (steepest descent of W) is −cof F : P, which must be positive.
TEST(StableNeoHookean, FiniteAndRestoringWhenFlatOrInverted) {
  for (const auto& F : test_gradients()) {
    if (F.determinant() > 0) continue;
    const Eigen::Matrix3d P = first_piola(kLaw, F);
    EXPECT_TRUE(std::isfinite(strain_energy_density(kLaw, F)));
    EXPECT_TRUE(P.allFinite());
    EXPECT_GT(-(cofactor(F).array() * P.array()).sum(), 0.0) << F;
  }
  // J is the only thing the volumetric term sees: along F = diag(1, 1, s) the energy falls
  // monotonically as s grows from −1 to 1 (no barrier, no well at J ≤ 0).
  double before = strain_energy_density(kLaw, Eigen::Vector3d(1, 1, -1).asDiagonal());
  for (double s = -0.9; s <= 1.0 + 1e-12; s += 0.1) {
    const double w = strain_energy_density(kLaw, Eigen::Vector3d(1, 1, s).asDiagonal());
    EXPECT_LT(w, before) << s;
    before = w;
  }
}

TEST(StableNeoHookean, TheVariantKnowsItIsInversionRobustAndTheOthersAreNot) {
  EXPECT_TRUE(inversion_robust(HyperelasticLaw(kLaw)));
  EXPECT_FALSE(inversion_robust(HyperelasticLaw(NeoHookean::from(NeoHookeanForm::paper, kPaper))));
  EXPECT_EQ(law_name(HyperelasticLaw(kLaw)), "stable_neo_hookean");
  const Eigen::Matrix3d F = Eigen::Vector3d(1.1, 0.9, -0.2).asDiagonal();
  EXPECT_EQ(first_piola(HyperelasticLaw(kLaw), F), first_piola(kLaw, F));
}

namespace {

// One tetrahedron on a fixed base triangle with its apex pushed through the base (J = −0.4),
// released at rest: a short damped explicit run.
struct InvertedTet {
  mesh::TetMesh mesh;
  dynamics::Scene scene;
  std::vector<double> u0;
  InvertedTet() {
    const double L = 0.01;
    mesh.nodes = {{0, 0, 0}, {L, 0, 0}, {0, L, 0}, {0, 0, L}};
    mesh.tets = {{0, 1, 2, 3}};
    dynamics::DisplacementConstraint base;
    base.name = "base";
    base.nodes = {0, 1, 2};
    scene.constraints = {base};
    u0.assign(12, 0.0);
    u0[11] = -1.4 * L;  // apex at z = −0.4 L: J = −0.4
  }
};

double apex_volume_ratio(const double* u, double L) { return (L + u[11]) / L; }

}  // namespace

TEST(StableNeoHookean, AnInvertedElementIsPushedBackOutByTheExplicitEngine) {
  InvertedTet t;
  const fem::Material mat = fem::Material::make(kPaper, kLaw);
  const std::vector<fem::ElementKind> kinds(1, fem::ElementKind::tled);
  fem::ElementSet set(t.mesh, kinds, mat);
  EXPECT_TRUE(set.inversion_allowed(fem::ElementKind::tled));
  dynamics::ExplicitOptions opt;
  opt.dt = 0.5 * dynamics::critical_time_step(t.mesh, kPaper).dt;
  opt.steps = 4000;
  opt.damping_alpha = 200.0;
  dynamics::ExplicitSolver solver(set, dynamics::lumped_mass(t.mesh, kPaper.density), t.scene, opt);
  solver.set_initial_state(t.u0, {});
  solver.reset();
  // The restoring force at the inverted start: the apex is pushed up (+z).
  double f[3];
  set.gather(3, f);
  EXPECT_LT(f[2], 0.0);  // internal (resisting) force points down: the net force −f points up
  solver.advance(opt.steps);
  const double J = apex_volume_ratio(solver.displacement(), 0.01);
  EXPECT_GT(J, 0.9);  // back out, near the rest shape
  EXPECT_LT(J, 1.1);
  for (const auto& s : solver.energies()) EXPECT_TRUE(std::isfinite(s.strain));
}

TEST(StableNeoHookean, TheSameInvertedElementIsAFailureForTheNeoHookeanLaw) {
  InvertedTet t;
  const fem::Material mat = fem::Material::make(kPaper, NeoHookeanForm::paper);
  const std::vector<fem::ElementKind> kinds(1, fem::ElementKind::tled);
  fem::ElementSet set(t.mesh, kinds, mat);
  EXPECT_FALSE(set.inversion_allowed(fem::ElementKind::tled));
  dynamics::ExplicitOptions opt;
  opt.dt = 0.5 * dynamics::critical_time_step(t.mesh, kPaper).dt;
  opt.steps = 10;
  dynamics::ExplicitSolver solver(set, dynamics::lumped_mass(t.mesh, kPaper.density), t.scene, opt);
  solver.set_initial_state(t.u0, {});
  EXPECT_THROW(solver.reset(), NumericalError);
}

// The vectorised TLED and ANP kernels of the law (fem/stable_kernels.hpp) against the reference
// element forces (fem/element_response.hpp, assembled with ANP's nodal pressures), on a state
// that inverts some elements: the same nodal forces to round-off, and no inverted element
// reported in the kernel statistics.
TEST(StableNeoHookean, TheExplicitKernelsGiveTheReferenceForcesAlsoForInvertedElements) {
  const auto m = test_scenes::cuboid(3, 3, 2, 0.03, 0.03, 0.02);
  const fem::Material mat = fem::Material::make(kPaper, kLaw);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> d(-0.006, 0.006);  // up to 0.6 of the 1 cm cell: inverts some
  std::vector<double> u(3 * m.nodes.size());
  for (double& x : u) x = d(rng);
  for (const fem::ElementKind kind : {fem::ElementKind::tled, fem::ElementKind::anp}) {
    const std::vector<fem::ElementKind> kinds(m.num_tets(), kind);
    fem::ElementSet set(m, kinds, mat);
    fem::KernelStats stats;
    set.compute(u.data(), stats);
    EXPECT_EQ(stats.min_j, 1e300);  // nothing reported: inverted elements are states here
    const fem::Assembler reference(m, kinds, mat);
    Eigen::VectorXd f;
    reference.internal_forces(u.data(), f);
    EXPECT_GT(reference.min_volume_ratio(u.data()), -1e300);
    EXPECT_LT(reference.min_volume_ratio(u.data()), 0.0) << "the state should invert an element";
    for (int i = 0; i < m.num_nodes(); ++i) {
      double g[3];
      set.gather(i, g);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(g[k], f[3 * i + k], 1e-10 * f.lpNorm<Eigen::Infinity>()) << i;
    }
  }
}
