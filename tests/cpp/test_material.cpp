// Material laws as physics: elastic constants and the wave speed of 000 eq. 35, stress as the
// derivative of the strain energy, objectivity, the shared small-strain limit of both
// neo-Hookean forms, consistent tangents, the polar decomposition, the closed-form
// uniaxial solutions that the FE tests compare against, and Mooney–Rivlin as a second
// hyperelastic law behind the same interface.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "softsim/io/errors.hpp"
#include "softsim/material/elastic.hpp"
#include "softsim/material/hyperelastic.hpp"
#include "softsim/material/mooney_rivlin.hpp"
#include "softsim/material/neo_hookean.hpp"
#include "softsim/material/polar_decomposition.hpp"
#include "softsim/material/small_strain.hpp"
#include "softsim/material/uniaxial.hpp"

#include "support/scenes.hpp"

using namespace softsim;
using namespace softsim::material;

namespace {

using test_scenes::kPaper;

Eigen::Matrix3d rotation(double angle, Eigen::Vector3d axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// A random deformation gradient with moderate stretch (J well away from 0).
Eigen::Matrix3d random_F(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> d(-amplitude, amplitude);
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) F(i, j) += d(rng);
  return rotation(d(rng) * 3.0, Eigen::Vector3d(1, 2, 3)) * F;
}

// Central-difference derivative of a scalar energy with respect to F.
template <class W>
Eigen::Matrix3d numeric_gradient(W w, const Eigen::Matrix3d& F, double h = 1e-6) {
  Eigen::Matrix3d G;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Eigen::Matrix3d Fp = F, Fm = F;
      Fp(i, j) += h;
      Fm(i, j) -= h;
      G(i, j) = (w(Fp) - w(Fm)) / (2 * h);
    }
  return G;
}

// Central-difference increment of a stress P(F) along dF.
template <class P>
Eigen::Matrix3d numeric_increment(P stress, const Eigen::Matrix3d& F, const Eigen::Matrix3d& dF, double h = 1e-6) {
  return (stress(F + h * dF) - stress(F - h * dF)) / (2 * h);
}

}  // namespace

TEST(Elastic, PaperConstantsGiveLameParametersAndWaveSpeed) {
  const LameParameters l = lame_parameters(kPaper);
  EXPECT_NEAR(l.mu, 5000.0 / 2.7, 1e-9);
  EXPECT_NEAR(l.lambda, 5000.0 * 0.35 / (1.35 * 0.3), 1e-9);
  EXPECT_NEAR(bulk_modulus(kPaper), l.lambda + 2.0 * l.mu / 3.0, 1e-9);
  // 000 eq. 35 is the P-wave speed sqrt((λ + 2μ)/ρ).
  EXPECT_NEAR(dilatational_wave_speed(kPaper), std::sqrt((l.lambda + 2 * l.mu) / kPaper.density), 1e-12);
  EXPECT_NEAR(dilatational_wave_speed(kPaper), std::sqrt(3250.0 / 405.0), 1e-12);
  const ElasticParameters back = from_lame(l.mu, l.lambda, kPaper.density);
  EXPECT_NEAR(back.youngs_modulus, 5000.0, 1e-9);
  EXPECT_NEAR(back.poisson_ratio, 0.35, 1e-14);
}

TEST(Elastic, RejectsUnphysicalConstants) {
  EXPECT_THROW(validate({-1.0, 0.3, 1000.0}), InputError);
  EXPECT_THROW(validate({1.0, 0.5, 1000.0}), InputError);
  EXPECT_THROW(validate({1.0, 0.3, 0.0}), InputError);
  EXPECT_NO_THROW(validate(kPaper));
}

class NeoHookeanForms : public ::testing::TestWithParam<NeoHookeanForm> {};

TEST_P(NeoHookeanForms, StressFreeAndEnergyFreeAtRest) {
  const NeoHookean law = NeoHookean::from(GetParam(), kPaper);
  EXPECT_LT(first_piola(law, Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(strain_energy_density(law, Eigen::Matrix3d::Identity()), 0.0, 1e-12);
}

TEST_P(NeoHookeanForms, FirstPiolaIsTheEnergyGradient) {
  const NeoHookean law = NeoHookean::from(GetParam(), kPaper);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.3);
    const Eigen::Matrix3d P = first_piola(law, F);
    const Eigen::Matrix3d G = numeric_gradient([&](const Eigen::Matrix3d& X) { return strain_energy_density(law, X); }, F);
    EXPECT_LT((P - G).norm(), 1e-6 * P.norm() + 1e-8) << "trial " << trial;
  }
}

TEST_P(NeoHookeanForms, SecondPiolaOfEq14IsConsistentWithP) {
  const NeoHookean law = NeoHookean::from(GetParam(), kPaper);
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.3);
    const Eigen::Matrix3d S = second_piola(law, F.transpose() * F);  // 000 eqs. 14–15
    EXPECT_LT((F * S - first_piola(law, F)).norm(), 1e-10 * S.norm());
    EXPECT_LT((S - S.transpose()).norm(), 1e-10 * S.norm());
  }
}

TEST_P(NeoHookeanForms, ObjectiveUnderRotation) {
  const NeoHookean law = NeoHookean::from(GetParam(), kPaper);
  std::mt19937 rng(3);
  const Eigen::Matrix3d F = random_F(rng, 0.3);
  const Eigen::Matrix3d Q = rotation(1.1, Eigen::Vector3d(-1, 0.5, 2));
  EXPECT_LT((first_piola(law, Q * F) - Q * first_piola(law, F)).norm(), 1e-10 * first_piola(law, F).norm());
  EXPECT_NEAR(strain_energy_density(law, Q * F), strain_energy_density(law, F), 1e-10);
}

TEST_P(NeoHookeanForms, LinearisesToSmallStrainElasticityWithTheSameConstants) {
  const NeoHookean law = NeoHookean::from(GetParam(), kPaper);
  const LameParameters l = lame_parameters(kPaper);
  Eigen::Matrix3d H;
  H << 0.3, -0.2, 0.1, 0.4, -0.1, 0.25, -0.3, 0.2, 0.15;
  // The difference from linear elasticity is second order in the strain amplitude.
  double previous = 0;
  for (double eps : {1e-3, 1e-4}) {
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + eps * H;
    const double diff = (first_piola(law, F) - linear_stress(l, F)).norm() / linear_stress(l, F).norm();
    EXPECT_LT(diff, 10 * eps);
    if (previous > 0) EXPECT_NEAR(diff / previous, 0.1, 0.02);
    previous = diff;
  }
}

TEST_P(NeoHookeanForms, TangentMatchesFiniteDifferenceOfStress) {
  const NeoHookean law = NeoHookean::from(GetParam(), kPaper);
  std::mt19937 rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.3);
    const Eigen::Matrix3d dF = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d fd =
        numeric_increment([&](const Eigen::Matrix3d& X) { return first_piola(law, X); }, F, dF);
    EXPECT_LT((first_piola_increment(law, F, dF) - fd).norm(), 1e-6 * fd.norm());
  }
}

INSTANTIATE_TEST_SUITE_P(BothForms, NeoHookeanForms,
                         ::testing::Values(NeoHookeanForm::paper, NeoHookeanForm::decoupled),
                         [](const auto& info) { return form_name(info.param); });

TEST(NeoHookean, FormsDifferAtLargeStrain) {
  // Same (E, ν) but different laws: at 30 % compression the stresses must not coincide, so
  // every comparison has to say which form it uses.
  const Eigen::Matrix3d F = Eigen::Vector3d(1.1, 1.1, 0.7).asDiagonal();
  const auto p = first_piola(NeoHookean::from(NeoHookeanForm::paper, kPaper), F);
  const auto d = first_piola(NeoHookean::from(NeoHookeanForm::decoupled, kPaper), F);
  EXPECT_GT((p - d).norm(), 0.01 * p.norm());
}

TEST(SmallStrain, LinearStressIsTheEnergyGradientButNotRotationInvariant) {
  const LameParameters l = lame_parameters(kPaper);
  std::mt19937 rng(1);
  const Eigen::Matrix3d F = random_F(rng, 0.2);
  const Eigen::Matrix3d G = numeric_gradient([&](const Eigen::Matrix3d& X) { return linear_energy_density(l, X); }, F);
  EXPECT_LT((linear_stress(l, F) - G).norm(), 1e-6 * G.norm());
  // A rigid 90° rotation produces a large spurious stress in small-strain elasticity.
  const Eigen::Matrix3d R = rotation(M_PI / 2, Eigen::Vector3d(0, 0, 1));
  EXPECT_GT(linear_stress(l, R).norm(), 0.5 * l.mu);
}

TEST(Corotated, StressFreeUnderRotationAndEnergyGradient) {
  const LameParameters l = lame_parameters(kPaper);
  const Eigen::Matrix3d R = rotation(M_PI / 2, Eigen::Vector3d(1, 1, 0));
  EXPECT_LT(corotated_first_piola(l, R).norm(), 1e-10 * l.mu);
  std::mt19937 rng(2);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.3);
    const Eigen::Matrix3d G =
        numeric_gradient([&](const Eigen::Matrix3d& X) { return corotated_energy_density(l, X); }, F);
    EXPECT_LT((corotated_first_piola(l, F) - G).norm(), 1e-6 * G.norm());
    const Eigen::Matrix3d Q = rotation(0.7 * trial, Eigen::Vector3d(0, 1, 1));
    EXPECT_LT((corotated_first_piola(l, Q * F) - Q * corotated_first_piola(l, F)).norm(), 1e-9 * G.norm());
  }
}

TEST(Corotated, TangentIncludesTheRotationVariation) {
  const LameParameters l = lame_parameters(kPaper);
  std::mt19937 rng(9);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.3);
    const Eigen::Matrix3d dF = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d fd =
        numeric_increment([&](const Eigen::Matrix3d& X) { return corotated_first_piola(l, X); }, F, dF);
    EXPECT_LT((corotated_first_piola_increment(l, F, dF) - fd).norm(), 1e-6 * fd.norm());
    // Without the dR term the tangent would be the plain linear one: make sure they differ.
    EXPECT_GT((linear_stress_increment(l, dF) - fd).norm(), 1e-3 * fd.norm());
  }
}

TEST(Polar, RotationTimesSymmetricStretch) {
  std::mt19937 rng(4);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::Matrix3d F = random_F(rng, 0.5);
    if (trial % 5 == 0) F = rotation(2.0, Eigen::Vector3d(1, -1, 2)) * Eigen::Vector3d(3.0, 0.3, 1.2).asDiagonal();
    if (F.determinant() <= 0.05) continue;
    const Polar p = polar_decomposition(F);
    EXPECT_LT((p.R.transpose() * p.R - Eigen::Matrix3d::Identity()).norm(), 1e-13);
    EXPECT_NEAR(p.R.determinant(), 1.0, 1e-13);
    EXPECT_LT((p.S - p.S.transpose()).norm(), 1e-14 * p.S.norm());
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(p.S).eigenvalues().minCoeff(), 0.0);
    EXPECT_LT((p.R * p.S - F).norm(), 1e-13 * F.norm());
  }
}

class UniaxialForms : public ::testing::TestWithParam<NeoHookeanForm> {};

TEST_P(UniaxialForms, ClosedFormSolvesTheLawItDescribes) {
  // The uniaxial solution is written from the energy independently of first_piola(): with
  // F = diag(λt, λt, λa) the law's P must have P11 = P22 = 0 and P33 = the nominal stress.
  const NeoHookean law = NeoHookean::from(GetParam(), kPaper);
  for (double a : {0.7, 0.85, 1.0, 1.2}) {
    const UniaxialSolution s = uniaxial_neo_hookean(law, a);
    const Eigen::Matrix3d F = Eigen::Vector3d(s.lateral_stretch, s.lateral_stretch, a).asDiagonal();
    const Eigen::Matrix3d P = first_piola(law, F);
    EXPECT_NEAR(P(0, 0), 0.0, 1e-9 * law.mu) << "stretch " << a;
    EXPECT_NEAR(P(1, 1), 0.0, 1e-9 * law.mu);
    EXPECT_NEAR(P(2, 2), s.nominal_stress, 1e-9 * law.mu);
  }
  // Compression expands laterally.
  EXPECT_GT(uniaxial_neo_hookean(law, 0.7).lateral_stretch, 1.0);
  EXPECT_LT(uniaxial_neo_hookean(law, 0.7).nominal_stress, 0.0);
}

TEST_P(UniaxialForms, SmallStrainLimitIsHookesLaw) {
  const NeoHookean law = NeoHookean::from(GetParam(), kPaper);
  const double a = 1.0 - 1e-5;
  const UniaxialSolution s = uniaxial_neo_hookean(law, a);
  const UniaxialSolution lin = uniaxial_linear(kPaper, a);
  EXPECT_NEAR(s.nominal_stress / lin.nominal_stress, 1.0, 1e-4);
  EXPECT_NEAR((s.lateral_stretch - 1.0) / (lin.lateral_stretch - 1.0), 1.0, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(BothForms, UniaxialForms, ::testing::Values(NeoHookeanForm::paper, NeoHookeanForm::decoupled),
                         [](const auto& info) { return form_name(info.param); });

// ---- Mooney–Rivlin (material/mooney_rivlin.hpp): a second law behind the same interface ----

namespace {

// C10, C01 and K of the order of the paper's tissue (μ = 2 (C10 + C01) = 2000 Pa).
const MooneyRivlin kMooneyRivlin{600.0, 400.0, 6000.0};

}  // namespace

TEST(MooneyRivlin, StressFreeAndEnergyFreeAtRest) {
  EXPECT_LT(first_piola(kMooneyRivlin, Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(strain_energy_density(kMooneyRivlin, Eigen::Matrix3d::Identity()), 0.0, 1e-12);
}

TEST(MooneyRivlin, SimpleShearMatchesRivlinsClosedForm) {
  // F = I + γ e₁⊗e₂ (J = 1): σ₁₂ = 2 (C10 + C01) γ, σ₁₁ − σ₂₂ = 2 (C10 + C01) γ² and
  // σ₂₂ − σ₃₃ = −2 C01 γ² (Rivlin 1948), whatever K. The last one separates C01 from C10.
  const double c10 = kMooneyRivlin.c10, c01 = kMooneyRivlin.c01;
  for (double gamma : {0.1, 0.5, 1.0}) {
    Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
    F(0, 1) = gamma;
    const Eigen::Matrix3d sigma = first_piola(kMooneyRivlin, F) * F.transpose();  // J = 1
    const double tol = 1e-12 * c10;
    EXPECT_NEAR(sigma(0, 1), 2.0 * (c10 + c01) * gamma, tol) << "gamma " << gamma;
    EXPECT_NEAR(sigma(1, 0), sigma(0, 1), tol);
    EXPECT_NEAR(sigma(0, 0) - sigma(1, 1), 2.0 * (c10 + c01) * gamma * gamma, tol);
    EXPECT_NEAR(sigma(1, 1) - sigma(2, 2), -2.0 * c01 * gamma * gamma, tol);
    EXPECT_NEAR(sigma(0, 2), 0.0, tol);
    EXPECT_NEAR(sigma(1, 2), 0.0, tol);
  }
}

TEST(MooneyRivlin, PureDilatationIsAPressureFromTheVolumetricTermAlone) {
  // F = s I: Ī₁ = Ī₂ = 3, so W = K/2 (J − 1)² and σ = K (J − 1) I with J = s³.
  for (double s : {0.9, 1.05}) {
    const Eigen::Matrix3d F = s * Eigen::Matrix3d::Identity();
    const double J = s * s * s;
    const Eigen::Matrix3d sigma = first_piola(kMooneyRivlin, F) * F.transpose() / J;
    const Eigen::Matrix3d expected = kMooneyRivlin.bulk * (J - 1.0) * Eigen::Matrix3d::Identity();
    EXPECT_LT((sigma - expected).norm(), 1e-10 * kMooneyRivlin.bulk);
    EXPECT_NEAR(strain_energy_density(kMooneyRivlin, F), 0.5 * kMooneyRivlin.bulk * (J - 1.0) * (J - 1.0),
                1e-10 * kMooneyRivlin.bulk);
  }
}

TEST(MooneyRivlin, FirstAndSecondPiolaAreTheEnergyGradient) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.3);
    const Eigen::Matrix3d P = first_piola(kMooneyRivlin, F);
    const Eigen::Matrix3d G =
        numeric_gradient([&](const Eigen::Matrix3d& X) { return strain_energy_density(kMooneyRivlin, X); }, F);
    EXPECT_LT((P - G).norm(), 1e-6 * P.norm() + 1e-8) << "trial " << trial;
    const Eigen::Matrix3d S = second_piola(kMooneyRivlin, F.transpose() * F);
    EXPECT_LT((F * S - P).norm(), 1e-10 * S.norm());
    EXPECT_LT((S - S.transpose()).norm(), 1e-10 * S.norm());
  }
}

TEST(MooneyRivlin, TangentMatchesFiniteDifferenceOfStress) {
  std::mt19937 rng(19);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.3);
    const Eigen::Matrix3d dF = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d fd =
        numeric_increment([&](const Eigen::Matrix3d& X) { return first_piola(kMooneyRivlin, X); }, F, dF);
    const Eigen::Matrix3d dP = first_piola_increment(kMooneyRivlin, linearise(kMooneyRivlin, F), dF);
    EXPECT_LT((dP - fd).norm(), 1e-6 * fd.norm()) << "trial " << trial;
  }
}

TEST(MooneyRivlin, ObjectiveUnderRotation) {
  std::mt19937 rng(23);
  const Eigen::Matrix3d F = random_F(rng, 0.3);
  const Eigen::Matrix3d Q = rotation(0.8, Eigen::Vector3d(1, -2, 0.5));
  const Eigen::Matrix3d P = first_piola(kMooneyRivlin, F);
  EXPECT_LT((first_piola(kMooneyRivlin, Q * F) - Q * P).norm(), 1e-10 * P.norm());
  EXPECT_NEAR(strain_energy_density(kMooneyRivlin, Q * F), strain_energy_density(kMooneyRivlin, F), 1e-10);
}

TEST(MooneyRivlin, WithoutC01IsTheDecoupledNeoHookeanToRoundOff) {
  // C01 = 0, C10 = μ/2, K: W of both is C10 (Ī₁ − 3) + K/2 (J − 1)².
  const NeoHookean nh = NeoHookean::from(NeoHookeanForm::decoupled, kPaper);
  const MooneyRivlin mr{nh.c10(), 0.0, nh.bulk};
  std::mt19937 rng(29);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.4);
    const Eigen::Matrix3d dF = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d P = first_piola(nh, F);
    EXPECT_LT((first_piola(mr, F) - P).norm(), 1e-13 * P.norm()) << "trial " << trial;
    const Eigen::Matrix3d C = F.transpose() * F;
    EXPECT_LT((second_piola(mr, C) - second_piola(nh, C)).norm(), 1e-13 * second_piola(nh, C).norm());
    EXPECT_NEAR(strain_energy_density(mr, F), strain_energy_density(nh, F), 1e-13 * nh.mu);
    const Eigen::Matrix3d dP = first_piola_increment(nh, F, dF);
    EXPECT_LT((first_piola_increment(mr, linearise(mr, F), dF) - dP).norm(), 1e-13 * dP.norm());
  }
}

TEST(MooneyRivlin, LinearisesToSmallStrainElasticityWithItsShearAndBulkModuli) {
  const ElasticParameters p = small_strain_parameters(kMooneyRivlin, 1000.0);
  const LameParameters l = lame_parameters(p);
  EXPECT_NEAR(l.mu, 2.0 * (kMooneyRivlin.c10 + kMooneyRivlin.c01), 1e-9);
  EXPECT_NEAR(bulk_modulus(p), kMooneyRivlin.bulk, 1e-9);
  Eigen::Matrix3d H;
  H << 0.3, -0.2, 0.1, 0.4, -0.1, 0.25, -0.3, 0.2, 0.15;
  double previous = 0;
  for (double eps : {1e-3, 1e-4}) {
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + eps * H;
    const double diff = (first_piola(kMooneyRivlin, F) - linear_stress(l, F)).norm() / linear_stress(l, F).norm();
    EXPECT_LT(diff, 10 * eps);
    if (previous > 0) EXPECT_NEAR(diff / previous, 0.1, 0.02);
    previous = diff;
  }
}

TEST(MooneyRivlin, IsochoricPartPlusVolumetricTermIsTheWholeLaw) {
  const MooneyRivlin iso = isochoric_part(kMooneyRivlin);
  const double kappa = volumetric_modulus(kMooneyRivlin);
  std::mt19937 rng(31);
  const Eigen::Matrix3d F = random_F(rng, 0.3);
  const double J = F.determinant();
  EXPECT_NEAR(strain_energy_density(iso, F) + 0.5 * kappa * (J - 1.0) * (J - 1.0),
              strain_energy_density(kMooneyRivlin, F), 1e-12 * kappa);
  // The volumetric part's P is κ (J − 1) cof F = κ J (J − 1) F⁻ᵀ.
  const Eigen::Matrix3d Pvol = kappa * J * (J - 1.0) * F.inverse().transpose();
  EXPECT_LT((first_piola(iso, F) + Pvol - first_piola(kMooneyRivlin, F)).norm(), 1e-12 * kappa);
}

TEST(MooneyRivlin, RejectsNonPositiveModuli) {
  EXPECT_THROW(validate_moduli(MooneyRivlin{-500.0, 400.0, 6000.0}), InputError);
  EXPECT_THROW(validate_moduli(MooneyRivlin{600.0, 400.0, 0.0}), InputError);
  EXPECT_NO_THROW(validate_moduli(kMooneyRivlin));
}

TEST(HyperelasticLaw, TheVariantDispatchesToTheLawItHolds) {
  // The interface on the variant (material/hyperelastic.hpp) gives each law's own results.
  std::mt19937 rng(37);
  const Eigen::Matrix3d F = random_F(rng, 0.3), dF = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
  const NeoHookean nh = NeoHookean::from(NeoHookeanForm::paper, kPaper);
  const HyperelasticLaw a = nh, b = kMooneyRivlin;
  EXPECT_EQ(law_name(a), "neo_hookean_paper");
  EXPECT_EQ(law_name(b), "mooney_rivlin");
  EXPECT_EQ(first_piola(a, F), first_piola(nh, F));
  EXPECT_EQ(first_piola(b, F), first_piola(kMooneyRivlin, F));
  EXPECT_EQ(first_piola_increment(b, linearise(b, F), dF),
            first_piola_increment(kMooneyRivlin, linearise(kMooneyRivlin, F), dF));
  EXPECT_EQ(volumetric_modulus(b), kMooneyRivlin.bulk);
  EXPECT_EQ(strain_energy_density(isochoric_part(a), F), strain_energy_density(isochoric_part(nh), F));
}
