// The transversely isotropic law (material/transversely_isotropic.hpp) as physics: stress-free
// at rest, η = 0 is the decoupled neo-Hookean law, an isochoric stretch along and across the
// fibre gives the closed-form Cauchy stress differences, P and dP are the derivatives of W and
// P, rotating body and fibre together rotates the stress, and the explicit kernel with a fibre
// per element equals the one-element reference with each element's own fibre.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include <Eigen/Dense>

#include "softsim/fem/element_response.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/material/hyperelastic.hpp"
#include "softsim/material/transversely_isotropic.hpp"
#include "softsim/material/viscoelastic.hpp"

#include "support/scenes.hpp"

using namespace softsim;
using namespace softsim::material;

namespace {

const TransverselyIsotropic kTI{1500.0, 4000.0, 20000.0, Eigen::Vector3d(1, 2, -2).normalized()};

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

Eigen::Matrix3d cauchy(const TransverselyIsotropic& law, const Eigen::Matrix3d& F) {
  return first_piola(law, F) * F.transpose() / F.determinant();
}

}  // namespace

TEST(TransverselyIsotropic, StressFreeAndEnergyFreeAtRest) {
  EXPECT_LT(first_piola(kTI, Eigen::Matrix3d::Identity()).norm(), 1e-12 * kTI.bulk);
  EXPECT_NEAR(strain_energy_density(kTI, Eigen::Matrix3d::Identity()), 0.0, 1e-12 * kTI.bulk);
}

TEST(TransverselyIsotropic, WithoutFibreStiffnessItIsTheDecoupledNeoHookean) {
  const NeoHookean nh = NeoHookean::from(NeoHookeanForm::decoupled, test_scenes::kPaper);
  TransverselyIsotropic ti{nh.mu, 0.0, nh.bulk, Eigen::Vector3d(0, 0.6, 0.8)};
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.3);
    const double scale = first_piola(nh, F).norm();
    EXPECT_LT((first_piola(ti, F) - first_piola(nh, F)).norm(), 1e-12 * scale);
    EXPECT_NEAR(strain_energy_density(ti, F), strain_energy_density(nh, F), 1e-12 * scale);
    const Eigen::Matrix3d dF = random_F(rng, 0.5) - Eigen::Matrix3d::Identity();
    EXPECT_LT((first_piola_increment(ti, linearise(ti, F), dF) - first_piola_increment(nh, F, dF)).norm(),
              1e-11 * scale);
  }
}

// Isochoric uniaxial stretch λ (J = 1) along the fibre a = e1: σ11 − σ22 = μ(λ² − 1/λ) +
// 2ηλ²(λ² − 1); across it (stretch along e2, fibre e1 in the transverse plane): the fibre term
// is the same in the two transverse directions, so σ22 − σ33 = μ(λ² − 1/λ) without η.
TEST(TransverselyIsotropic, IsochoricStretchAlongAndAcrossTheFibreMatchesTheClosedForm) {
  TransverselyIsotropic ti = kTI;
  ti.fibre = Eigen::Vector3d::UnitX();
  for (double lambda : {0.7, 0.95, 1.1, 1.4}) {
    const double t = 1.0 / std::sqrt(lambda);
    const Eigen::Matrix3d along = cauchy(ti, Eigen::Vector3d(lambda, t, t).asDiagonal());
    const double expected_along = ti.mu * (lambda * lambda - 1 / lambda) + 2 * ti.eta * lambda * lambda * (lambda * lambda - 1);
    EXPECT_NEAR(along(0, 0) - along(1, 1), expected_along, 1e-10 * ti.bulk);
    EXPECT_NEAR(along(1, 1), along(2, 2), 1e-10 * ti.bulk);
    const Eigen::Matrix3d across = cauchy(ti, Eigen::Vector3d(t, lambda, t).asDiagonal());
    EXPECT_NEAR(across(1, 1) - across(2, 2), ti.mu * (lambda * lambda - 1 / lambda), 1e-10 * ti.bulk);
    // The fibre, shortened to 1/√λ, pulls (λ < 1: stretched fibre) or pushes along e1 only.
    const double expected_fibre = ti.mu * (1 / lambda - 1 / lambda) + 2 * ti.eta * (1 / lambda) * (1 / lambda - 1);
    EXPECT_NEAR(across(0, 0) - across(2, 2), expected_fibre, 1e-10 * ti.bulk);
  }
}

TEST(TransverselyIsotropic, FirstPiolaAndTangentAreTheDerivatives) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 30; ++trial) {
    TransverselyIsotropic ti = kTI;
    ti.fibre = (random_F(rng, 1.0) * Eigen::Vector3d(1, 0.3, -0.2)).normalized();
    const Eigen::Matrix3d F = random_F(rng, 0.3);
    const double h = 1e-6;
    Eigen::Matrix3d G;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Eigen::Matrix3d Fp = F, Fm = F;
        Fp(i, j) += h;
        Fm(i, j) -= h;
        G(i, j) = (strain_energy_density(ti, Fp) - strain_energy_density(ti, Fm)) / (2 * h);
      }
    const Eigen::Matrix3d P = first_piola(ti, F);
    EXPECT_LT((P - G).norm(), 1e-6 * P.norm() + 1e-6);
    EXPECT_LT((F * second_piola(ti, F.transpose() * F) - P).norm(), 1e-10 * P.norm());
    const Eigen::Matrix3d dF = random_F(rng, 0.5) - Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d numeric = (first_piola(ti, F + h * dF) - first_piola(ti, F - h * dF)) / (2 * h);
    const Eigen::Matrix3d dP = first_piola_increment(ti, linearise(ti, F), dF);
    EXPECT_LT((dP - numeric).norm(), 1e-6 * dP.norm() + 1e-6);
  }
}

// Objectivity (W(QF) = W(F), P(QF) = Q P(F)) and material symmetry carried by the fibre:
// rotating the body and its fibre together (F → Q F Qᵀ, a → Q a) rotates P to Q P Qᵀ and keeps W.
TEST(TransverselyIsotropic, RotatingBodyAndFibreTogetherRotatesTheStress) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d F = random_F(rng, 0.3);
    const Eigen::Matrix3d Q = rotation(0.3 + trial, Eigen::Vector3d(trial, 1, -2));
    const Eigen::Matrix3d P = first_piola(kTI, F);
    EXPECT_LT((first_piola(kTI, Q * F) - Q * P).norm(), 1e-10 * P.norm());
    TransverselyIsotropic rotated = kTI;
    rotated.fibre = Q * kTI.fibre;
    EXPECT_LT((first_piola(rotated, Q * F * Q.transpose()) - Q * P * Q.transpose()).norm(), 1e-10 * P.norm());
    EXPECT_NEAR(strain_energy_density(rotated, Q * F * Q.transpose()), strain_energy_density(kTI, F),
                1e-10 * P.norm());
    // A different fibre is a different material: the stress is not merely rotated.
    EXPECT_GT((first_piola(kTI, Q * F * Q.transpose()) - Q * P * Q.transpose()).norm(), 1e-6 * P.norm());
  }
}

TEST(TransverselyIsotropic, ExplicitKernelUsesEachElementsOwnFibre) {
  const mesh::TetMesh m = test_scenes::cuboid(3, 2, 2, 0.03, 0.02, 0.02);
  fem::Material mat = fem::Material::make(small_strain_parameters(kTI, 1000.0), kTI);
  auto fibres = std::make_shared<std::vector<Eigen::Vector3d>>();
  for (int e = 0; e < m.num_tets(); ++e)
    fibres->push_back(Eigen::Vector3d(std::cos(0.4 * e), std::sin(0.4 * e), 0.3 * (e % 3 - 1)).normalized());
  mat.fibres = fibres;
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> d(-1e-3, 1e-3);
  std::vector<double> u(3 * m.num_nodes());
  for (double& x : u) x = d(rng);
  {
    const fem::ElementKind kind = fem::ElementKind::tled;
    fem::ElementSet set(m, std::vector<fem::ElementKind>(m.num_tets(), kind), mat);
    fem::KernelStats st;
    set.compute(u.data(), st);
    std::vector<Eigen::Vector3d> expected(m.num_nodes(), Eigen::Vector3d::Zero());
    for (int e = 0; e < m.num_tets(); ++e) {
      const fem::Corners f = fem::element_forces(mat.for_element(e), kind, fem::tet_shape(m, e),
                                                 fem::corner_displacements(m, e, u.data()));
      for (int a = 0; a < 4; ++a) expected[m.tets[e][a]] += f[a];
    }
    double scale = 0;
    for (const auto& f : expected) scale = std::max(scale, f.norm());
    for (int n = 0; n < m.num_nodes(); ++n) {
      double f[3];
      set.gather(n, f);
      EXPECT_LT((Eigen::Vector3d(f[0], f[1], f[2]) - expected[n]).norm(), 1e-11 * scale) << "node " << n;
    }
    // The same forces with the uniform fibre would differ: the per-element directions are used.
    fem::ElementSet uniform(m, std::vector<fem::ElementKind>(m.num_tets(), kind),
                            fem::Material::make(small_strain_parameters(kTI, 1000.0), kTI));
    uniform.compute(u.data(), st);
    double diff = 0;
    for (int n = 0; n < m.num_nodes(); ++n) {
      double f[3];
      uniform.gather(n, f);
      diff = std::max(diff, (Eigen::Vector3d(f[0], f[1], f[2]) - expected[n]).norm());
    }
    EXPECT_GT(diff, 1e-3 * scale);
  }
}

// Under a homogeneous deformation every nodal volume ratio is the elements' J, so the ANP
// element (isochoric law per element, U(J) at the nodes) is TLED exactly: also with a fibre per
// element, and with a Prony series advancing its internal variables step by step.
TEST(TransverselyIsotropic, AnpEqualsTledUnderAHomogeneousDeformationWithFibresAndRelaxation) {
  const mesh::TetMesh m = test_scenes::cuboid(3, 2, 2, 0.03, 0.02, 0.02);
  Viscoelastic v;
  v.base = kTI;
  v.terms = 1;
  v.g[0] = 0.4;
  v.tau[0] = 0.01;
  auto fibres = std::make_shared<std::vector<Eigen::Vector3d>>();
  for (int e = 0; e < m.num_tets(); ++e) fibres->push_back(Eigen::Vector3d(1, 0.1 * (e % 5), 0).normalized());
  Eigen::Matrix3d F;
  F << 1.1, 0.05, 0.0, 0.02, 0.93, 0.01, 0.0, 0.03, 1.02;
  std::vector<double> u(3 * m.num_nodes());
  for (int i = 0; i < m.num_nodes(); ++i)
    for (int k = 0; k < 3; ++k) u[3 * i + k] = ((F - Eigen::Matrix3d::Identity()) * m.nodes[i])[k];
  for (const material::HyperelasticLaw& law : {material::HyperelasticLaw(kTI), material::HyperelasticLaw(v)}) {
    fem::Material mat = fem::Material::make(small_strain_parameters(kTI, 1000.0), law);
    mat.fibres = fibres;
    fem::ElementSet tled(m, std::vector<fem::ElementKind>(m.num_tets(), fem::ElementKind::tled), mat);
    fem::ElementSet anp(m, std::vector<fem::ElementKind>(m.num_tets(), fem::ElementKind::anp), mat);
    for (int s = 0; s < 5; ++s) {
      fem::KernelStats st;
      tled.compute(u.data(), st, {s, 1e-3});
      anp.compute(u.data(), st, {s, 1e-3});
      double scale = 0, err = 0;
      for (int n = 0; n < m.num_nodes(); ++n) {
        double a[3], b[3];
        tled.gather(n, a);
        anp.gather(n, b);
        for (int k = 0; k < 3; ++k) {
          scale = std::max(scale, std::abs(a[k]));
          err = std::max(err, std::abs(a[k] - b[k]));
        }
      }
      EXPECT_LT(err, 1e-11 * scale) << law_name(law) << " step " << s;
    }
  }
}
