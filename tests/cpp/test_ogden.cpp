// The Ogden law (material/ogden.hpp) as physics: its special cases are the decoupled
// neo-Hookean and Mooney–Rivlin laws, a homogeneous uniaxial stretch gives the closed-form
// incompressible Ogden stress, P and dP are the derivatives of W and P (also where principal
// stretches coincide, the case the eigen-decomposition must survive), and it is objective.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "softsim/io/errors.hpp"
#include "softsim/material/hyperelastic.hpp"
#include "softsim/material/mooney_rivlin.hpp"
#include "softsim/material/neo_hookean.hpp"
#include "softsim/material/ogden.hpp"

#include "support/scenes.hpp"

using namespace softsim;
using namespace softsim::material;

namespace {

// A three-term law with mixed-sign exponents (shear modulus ½ Σ μ_p α_p = 1215 Pa).
const Ogden kOgden{3, {700.0, 30.0, -100.0}, {1.3, 5.0, -2.0}, 8000.0};

Eigen::Matrix3d rotation(double angle, Eigen::Vector3d axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Eigen::Matrix3d random_F(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> d(-amplitude, amplitude);
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) F(i, j) += d(rng);
  return rotation(d(rng) * 3.0, Eigen::Vector3d(1, 2, 3)) * F;
}

Eigen::Matrix3d numeric_gradient(const Ogden& law, const Eigen::Matrix3d& F, double h = 1e-6) {
  Eigen::Matrix3d G;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Eigen::Matrix3d Fp = F, Fm = F;
      Fp(i, j) += h;
      Fm(i, j) -= h;
      G(i, j) = (strain_energy_density(law, Fp) - strain_energy_density(law, Fm)) / (2 * h);
    }
  return G;
}

Eigen::Matrix3d numeric_increment(const Ogden& law, const Eigen::Matrix3d& F, const Eigen::Matrix3d& dF,
                                  double h = 1e-6) {
  return (first_piola(law, F + h * dF) - first_piola(law, F - h * dF)) / (2 * h);
}

// Deformations with coinciding principal stretches: rest, a rotated equibiaxial stretch (two
// equal), a rotated dilatation (three equal), and two stretches 1e-9 apart (the quotient's
// worst case, handled by the limit).
std::vector<Eigen::Matrix3d> equal_stretch_cases() {
  const Eigen::Matrix3d Q = rotation(0.7, Eigen::Vector3d(1, -2, 0.5));
  return {Eigen::Matrix3d::Identity(),
          Q * Eigen::Vector3d(1.2, 1.2, 0.75).asDiagonal() * Q.transpose(),
          Q * (1.1 * Eigen::Matrix3d::Identity()),
          Q * Eigen::Vector3d(0.9, 0.9 + 1e-9, 1.3).asDiagonal()};
}

}  // namespace

TEST(Ogden, StressFreeAndEnergyFreeAtRest) {
  EXPECT_LT(first_piola(kOgden, Eigen::Matrix3d::Identity()).norm(), 1e-12 * kOgden.bulk);
  EXPECT_NEAR(strain_energy_density(kOgden, Eigen::Matrix3d::Identity()), 0.0, 1e-12 * kOgden.bulk);
}

TEST(Ogden, OneTermWithAlphaTwoIsTheDecoupledNeoHookean) {
  // (μ/2)(Σ λ̄_i² − 3) = (μ/2)(Ī₁ − 3): the eigen-decomposition scheme equals the invariant one.
  const NeoHookean nh = NeoHookean::from(NeoHookeanForm::decoupled, test_scenes::kPaper);
  const Ogden og{1, {nh.mu}, {2.0}, nh.bulk};
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.4);
    const Eigen::Matrix3d dF = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d P = first_piola(nh, F);
    EXPECT_LT((first_piola(og, F) - P).norm(), 1e-12 * P.norm()) << "trial " << trial;
    const Eigen::Matrix3d C = F.transpose() * F;
    EXPECT_LT((second_piola(og, C) - second_piola(nh, C)).norm(), 1e-12 * second_piola(nh, C).norm());
    EXPECT_NEAR(strain_energy_density(og, F), strain_energy_density(nh, F), 1e-12 * nh.mu);
    const Eigen::Matrix3d dP = first_piola_increment(nh, F, dF);
    EXPECT_LT((first_piola_increment(og, linearise(og, F), dF) - dP).norm(), 1e-12 * dP.norm());
  }
}

TEST(Ogden, TwoTermsWithAlphaPlusMinusTwoAreMooneyRivlin) {
  // Σ λ̄_i⁻² = Ī₂ since λ̄₁λ̄₂λ̄₃ = 1: C10 = μ₁/2, C01 = −μ₂/2.
  const MooneyRivlin mr{600.0, 400.0, 6000.0};
  const Ogden og{2, {2.0 * mr.c10, -2.0 * mr.c01}, {2.0, -2.0}, mr.bulk};
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.4);
    const Eigen::Matrix3d dF = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d P = first_piola(mr, F);
    EXPECT_LT((first_piola(og, F) - P).norm(), 1e-12 * P.norm()) << "trial " << trial;
    EXPECT_NEAR(strain_energy_density(og, F), strain_energy_density(mr, F), 1e-12 * mr.bulk);
    const Eigen::Matrix3d dP = first_piola_increment(mr, linearise(mr, F), dF);
    EXPECT_LT((first_piola_increment(og, linearise(og, F), dF) - dP).norm(), 1e-11 * dP.norm());
  }
}

TEST(Ogden, UniaxialStretchApproachesTheIncompressibleClosedForm) {
  // Incompressible uniaxial tension, F = diag(λ, λ^(−1/2), λ^(−1/2)), lateral stress zero:
  // P₁₁ = Σ_p μ_p (λ^(α_p − 1) − λ^(−α_p/2 − 1)) (Ogden 1972). With K = 10⁶ μ the lateral
  // stretch t that frees the lateral faces is found by bisection; the axial stress then
  // differs from the incompressible one by O(μ/K).
  Ogden law = kOgden;
  law.bulk = 1e6 * law.shear_modulus();
  for (double lambda : {0.7, 1.3, 2.0}) {
    double lo = 0.2, hi = 2.0;
    for (int it = 0; it < 200; ++it) {
      const double t = 0.5 * (lo + hi);
      const double lateral = first_piola(law, Eigen::Vector3d(lambda, t, t).asDiagonal().toDenseMatrix())(1, 1);
      (lateral > 0 ? hi : lo) = t;
    }
    const double t = 0.5 * (lo + hi);
    const Eigen::Matrix3d P = first_piola(law, Eigen::Vector3d(lambda, t, t).asDiagonal().toDenseMatrix());
    double expected = 0;
    for (int p = 0; p < law.terms; ++p)
      expected += law.mu[p] * (std::pow(lambda, law.alpha[p] - 1.0) - std::pow(lambda, -0.5 * law.alpha[p] - 1.0));
    EXPECT_NEAR(P(0, 0), expected, 1e-4 * std::abs(expected)) << "stretch " << lambda;
    EXPECT_NEAR(t, 1.0 / std::sqrt(lambda), 1e-5) << "stretch " << lambda;
  }
}

TEST(Ogden, FirstAndSecondPiolaAreTheEnergyGradient) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.4);
    const Eigen::Matrix3d P = first_piola(kOgden, F);
    EXPECT_LT((P - numeric_gradient(kOgden, F)).norm(), 1e-6 * P.norm()) << "trial " << trial;
    const Eigen::Matrix3d S = second_piola(kOgden, F.transpose() * F);
    EXPECT_LT((F * S - P).norm(), 1e-12 * P.norm()) << "trial " << trial;
  }
}

TEST(Ogden, StressIsTheEnergyGradientAtEqualStretches) {
  for (const Eigen::Matrix3d& F : equal_stretch_cases()) {
    const Eigen::Matrix3d P = first_piola(kOgden, F);
    EXPECT_LT((P - numeric_gradient(kOgden, F)).norm(), 1e-6 * kOgden.bulk) << F;
  }
}

TEST(Ogden, TangentMatchesFiniteDifferenceOfStress) {
  std::mt19937 rng(23);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.4);
    const Eigen::Matrix3d dF = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d fd = numeric_increment(kOgden, F, dF);
    const Eigen::Matrix3d dP = first_piola_increment(kOgden, linearise(kOgden, F), dF);
    EXPECT_LT((dP - fd).norm(), 1e-6 * fd.norm()) << "trial " << trial;
  }
}

TEST(Ogden, TangentMatchesFiniteDifferenceAtEqualStretches) {
  std::mt19937 rng(31);
  for (const Eigen::Matrix3d& F : equal_stretch_cases())
    for (int trial = 0; trial < 5; ++trial) {
      const Eigen::Matrix3d dF = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
      const Eigen::Matrix3d fd = numeric_increment(kOgden, F, dF);
      const Eigen::Matrix3d dP = first_piola_increment(kOgden, linearise(kOgden, F), dF);
      EXPECT_TRUE(dP.allFinite());
      EXPECT_LT((dP - fd).norm(), 1e-6 * fd.norm()) << F;
    }
}

TEST(Ogden, ObjectiveUnderRotation) {
  std::mt19937 rng(37);
  const Eigen::Matrix3d F = random_F(rng, 0.4);
  const Eigen::Matrix3d Q = rotation(1.1, Eigen::Vector3d(-1, 2, 3));
  const Eigen::Matrix3d P = first_piola(kOgden, F);
  EXPECT_LT((first_piola(kOgden, Q * F) - Q * P).norm(), 1e-10 * P.norm());
  EXPECT_NEAR(strain_energy_density(kOgden, Q * F), strain_energy_density(kOgden, F), 1e-10 * kOgden.bulk);
  const Eigen::Matrix3d dF = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d dP = first_piola_increment(kOgden, linearise(kOgden, F), dF);
  EXPECT_LT((first_piola_increment(kOgden, linearise(kOgden, Q * F), Q * dF) - Q * dP).norm(), 1e-10 * dP.norm());
}

TEST(Ogden, IsochoricPartPlusVolumetricTermIsTheWholeLaw) {
  const Ogden iso = isochoric_part(kOgden);
  const double kappa = volumetric_modulus(kOgden);
  EXPECT_EQ(kappa, kOgden.bulk);
  std::mt19937 rng(41);
  const Eigen::Matrix3d F = random_F(rng, 0.3);
  const double J = F.determinant();
  const Eigen::Matrix3d Pvol = kappa * J * (J - 1.0) * F.inverse().transpose();
  EXPECT_LT((first_piola(iso, F) + Pvol - first_piola(kOgden, F)).norm(), 1e-12 * kappa);
}

TEST(Ogden, LinearisesToItsShearAndBulkModuli) {
  const ElasticParameters p = small_strain_parameters(kOgden, 1000.0);
  const double mu = p.youngs_modulus / (2.0 * (1.0 + p.poisson_ratio));
  EXPECT_NEAR(mu, 0.5 * (700.0 * 1.3 + 30.0 * 5.0 + 100.0 * 2.0), 1e-9);
  // Simple shear γ = 1e-6: σ₁₂ = μ γ to first order.
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F(0, 1) = 1e-6;
  EXPECT_NEAR(first_piola(kOgden, F)(0, 1), mu * 1e-6, 1e-6 * mu * 1e-6);
}

TEST(Ogden, RejectsBadTerms) {
  EXPECT_NO_THROW(validate_moduli(kOgden));
  EXPECT_THROW(validate_moduli(Ogden{0, {}, {}, 1000.0}), InputError);
  EXPECT_THROW(validate_moduli(Ogden{1, {100.0}, {0.0}, 1000.0}), InputError);
  EXPECT_THROW(validate_moduli(Ogden{1, {100.0}, {-2.0}, 1000.0}), InputError);  // Σ μ_p α_p < 0
  EXPECT_THROW(validate_moduli(Ogden{1, {100.0}, {2.0}, 0.0}), InputError);
}

TEST(Ogden, TheVariantDispatchesToIt) {
  const HyperelasticLaw law = kOgden;
  std::mt19937 rng(43);
  const Eigen::Matrix3d F = random_F(rng, 0.3);
  const Eigen::Matrix3d dF = random_F(rng, 1.0) - Eigen::Matrix3d::Identity();
  EXPECT_EQ(law_name(law), "ogden");
  EXPECT_EQ(first_piola(law, F), first_piola(kOgden, F));
  EXPECT_EQ(first_piola_increment(law, linearise(law, F), dF), first_piola_increment(kOgden, linearise(kOgden, F), dF));
}
