// The vectorised law kernels (fem/invariant_kernels.hpp, fem/ogden_kernels.hpp) against the
// laws' own scalar P(F) (material/*.hpp), element by element on random tetrahedra and random
// deformations: Mooney–Rivlin, the transversely isotropic law (one fibre, a fibre per element),
// Ogden with one to three terms (α = 2 among them, and repeated and nearly repeated principal
// stretches), Prony series on each base with the internal-variable update fused into the pass,
// TLED and ANP, inverted elements and elements outside the Newton cube root's range. The
// closed-form principal values of C and the vectorisable pow are checked against Eigen's
// solver and std::pow.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Dense>

#include "softsim/fem/law_kernels.hpp"
#include "softsim/fem/ogden_kernels.hpp"
#include "softsim/fem/vector_pow.hpp"
#include "softsim/material/hyperelastic.hpp"

using namespace softsim;
using namespace softsim::material;

namespace {

Eigen::Matrix3d rotation(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// n separate tetrahedra (4 nodes each, random shapes) deformed by the given F's, in the kernels'
// structure-of-arrays layout; the reference forces ⁰V P ∇N from the law's own first_piola.
struct Batch {
  int n = 0;
  std::vector<int> n0, n1, n2, n3;
  std::vector<double> g[9], vol, out, u, scratch, pressure;
  std::vector<double> fibre[3];
  std::vector<Eigen::Matrix3d> F;
  std::vector<Eigen::Vector3d> grad[3];

  Batch(const std::vector<Eigen::Matrix3d>& Fs, std::mt19937& rng) : n(static_cast<int>(Fs.size())), F(Fs) {
    std::uniform_real_distribution<double> d(-0.3, 0.3);
    vol.resize(n), out.assign(12 * n, 0.0), u.resize(12 * n), scratch.assign(n, 0.0), pressure.resize(12 * n);
    for (auto& c : g) c.resize(n);
    for (auto& c : fibre) c.resize(n);
    for (auto& c : grad) c.resize(n);
    for (int e = 0; e < n; ++e) {
      Eigen::Matrix3d Dm = Eigen::Matrix3d::Identity() * 0.01;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) Dm(i, j) += 0.01 * d(rng);
      if (Dm.determinant() < 0) Dm.col(0) *= -1.0;
      const Eigen::Matrix3d inv = Dm.inverse();
      vol[e] = Dm.determinant() / 6.0;
      const Eigen::Vector3d X0(d(rng), d(rng), d(rng));
      const Eigen::Vector3d X[4] = {X0, X0 + Dm.col(0), X0 + Dm.col(1), X0 + Dm.col(2)};
      n0.push_back(12 * e), n1.push_back(12 * e + 3), n2.push_back(12 * e + 6), n3.push_back(12 * e + 9);
      for (int a = 0; a < 4; ++a)
        for (int c = 0; c < 3; ++c) u[12 * e + 3 * a + c] = ((F[e] - Eigen::Matrix3d::Identity()) * X[a])[c];
      for (int b = 0; b < 3; ++b) {
        grad[b][e] = inv.row(b).transpose();
        for (int c = 0; c < 3; ++c) g[3 * b + c][e] = grad[b][e][c];
      }
      const Eigen::Vector3d a = Eigen::Vector3d(d(rng), d(rng), d(rng) + 0.5).normalized();
      for (int c = 0; c < 3; ++c) fibre[c][e] = a[c];
      for (int a4 = 0; a4 < 4; ++a4) pressure[12 * e + 3 * a4] = 2000.0 * d(rng);
    }
  }

  fem::kernels::SoaView view() {
    fem::kernels::SoaView s{};
    s.n0 = n0.data(), s.n1 = n1.data(), s.n2 = n2.data(), s.n3 = n3.data();
    for (int i = 0; i < 9; ++i) s.g[i] = g[i].data();
    s.vol = vol.data(), s.out = out.data(), s.stride = n;
    return s;
  }

  double mean_pressure(int e) const {
    return 0.25 * (pressure[12 * e] + pressure[12 * e + 3] + pressure[12 * e + 6] + pressure[12 * e + 9]);
  }

  // Largest difference between the kernel's corner forces of element e and ⁰V P ∇N, relative
  // to the forces ⁰V |∇N| `stress` of a stress of that size (at least the largest reference
  // force): round-off is relative to the terms summed, not to a sum that nearly cancels.
  double error(int e, const Eigen::Matrix3d& P, double stress) const {
    double worst = 0, scale = 0;
    for (int b = 0; b < 3; ++b) scale = std::max(scale, vol[e] * stress * grad[b][e].norm());
    Eigen::Vector3d f[4];
    f[0].setZero();
    for (int b = 0; b < 3; ++b) f[b + 1] = vol[e] * P * grad[b][e], f[0] -= f[b + 1];
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::abs(out[(3 * a + c) * n + e] - f[a][c]));
        scale = std::max(scale, std::abs(f[a][c]));
      }
    return worst / scale;
  }
};

// Random deformations (up to 30 % strain, any rotation), plus an inverted element and two
// outside the Newton root's range of J (cube_root.hpp).
std::vector<Eigen::Matrix3d> random_deformations(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> d(-0.3, 0.3);
  std::vector<Eigen::Matrix3d> Fs;
  for (int e = 0; e < n; ++e) {
    Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) F(i, j) += d(rng);
    Fs.push_back(rotation(10.0 * d(rng), Eigen::Vector3d(1, 2, 3)) * F);
  }
  Fs.push_back(Eigen::Vector3d(-1.0, 1.0, 1.0).asDiagonal());
  Fs.push_back(Eigen::Matrix3d::Identity() * 2.5);
  Fs.push_back(Eigen::Matrix3d::Identity() * 0.45);
  return Fs;
}

// Principal stretches (λ, λ(1 + δ), λ(1 + δ')) in rotated axes: repeated and nearly repeated.
std::vector<Eigen::Matrix3d> near_repeated_deformations(std::mt19937& rng) {
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  std::vector<Eigen::Matrix3d> Fs;
  for (double delta : {0.0, 1e-15, 1e-12, 1e-9, 1e-7, 1e-5, 1e-3, 0.1})
    for (int pattern = 0; pattern < 4; ++pattern) {
      const double l = 1.0 + 0.2 * d(rng);
      const Eigen::Vector3d stretches = pattern == 0   ? Eigen::Vector3d(l, l * (1 + delta), 0.8)
                                        : pattern == 1 ? Eigen::Vector3d(1.3, l, l * (1 - delta))
                                        : pattern == 2 ? Eigen::Vector3d(l, l * (1 + delta), l * (1 - delta))
                                                       : Eigen::Vector3d(l, l * (1 + delta), l * (1 + 2 * delta));
      const Eigen::Matrix3d R = rotation(3.0 * d(rng), Eigen::Vector3d(d(rng), d(rng), 1.0));
      const Eigen::Matrix3d Q = rotation(3.0 * d(rng), Eigen::Vector3d(1.0, d(rng), d(rng)));
      Fs.push_back(R * stretches.asDiagonal() * Q.transpose());
    }
  Fs.push_back(Eigen::Matrix3d::Identity());
  Fs.push_back(rotation(0.7, Eigen::Vector3d(1, 1, 0)));
  return Fs;
}

const NeoHookean kNH = NeoHookean::from(NeoHookeanForm::decoupled, ElasticParameters{5000.0, 0.35, 1000.0});
// The stresses' round-off floor: a rigid rotation's P is round-off of the shear modulus.
const double kStressScale = kNH.mu;

// TLED (pressure = false) or ANP with `law`: the kernel against ⁰V (P(F) [+ p̄ cof F]) ∇N,
// zero forces where J ≤ 0; per-element fibres where `per_element_fibres`.
double worst_error(const HyperelasticLaw& law, Batch& b, bool anp, bool per_element_fibres) {
  fem::kernels::LawData data;
  if (per_element_fibres)
    for (int c = 0; c < 3; ++c) data.fibre[c] = b.fibre[c].data();
  data.stride = b.n;
  double min_j = 1e300;
  if (anp)
    fem::kernels::anp_forces(isochoric_part(law), b.view(), b.u.data(), 0, b.n, b.pressure.data(), b.scratch.data(),
                             min_j, data);
  else
    fem::kernels::tled_forces(law, b.view(), b.u.data(), 0, b.n, b.scratch.data(), min_j, data);
  double worst = 0;
  for (int e = 0; e < b.n; ++e) {
    HyperelasticLaw l = anp ? isochoric_part(law) : law;
    if (per_element_fibres) set_fibre(l, Eigen::Vector3d(b.fibre[0][e], b.fibre[1][e], b.fibre[2][e]));
    const Eigen::Matrix3d& F = b.F[e];
    const double J = F.determinant();
    Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
    double stress = kStressScale;
    if (J > 0) {
      P = first_piola(l, F);
      stress += P.norm();
      if (anp) {
        const Eigen::Matrix3d pressure = b.mean_pressure(e) * J * F.inverse().transpose();
        P += pressure;
        stress += pressure.norm();
      }
    }
    worst = std::max(worst, b.error(e, P, stress));
  }
  return worst;
}


Ogden ogden(int terms) {
  Ogden o;
  o.terms = terms;
  o.mu = {1200.0, -300.0, 40.0};
  o.alpha = {terms == 1 ? 2.0 : 6.5, -4.2, 1.3};
  o.bulk = kNH.bulk;
  if (terms == 1) o.mu[0] = kNH.mu;
  return o;
}

}  // namespace

TEST(LawKernels, MooneyRivlinEqualsTheScalarLaw) {
  std::mt19937 rng(1);
  for (double c01 : {0.0, 0.3 * kNH.mu}) {
    const HyperelasticLaw law = MooneyRivlin{0.5 * kNH.mu - c01, c01, kNH.bulk};
    for (bool anp : {false, true}) {
      Batch b(random_deformations(rng, 61), rng);
      EXPECT_LT(worst_error(law, b, anp, false), 1e-12) << "C01 " << c01 << " anp " << anp;
    }
  }
}

TEST(LawKernels, TransverselyIsotropicEqualsTheScalarLawWithOneFibreOrOnePerElement) {
  std::mt19937 rng(2);
  const HyperelasticLaw law = TransverselyIsotropic{kNH.mu, 3.0 * kNH.mu, kNH.bulk, Eigen::Vector3d(1, 2, -2).normalized()};
  for (bool anp : {false, true})
    for (bool per_element : {false, true}) {
      Batch b(random_deformations(rng, 61), rng);
      EXPECT_LT(worst_error(law, b, anp, per_element), 1e-12) << "anp " << anp << " per element " << per_element;
    }
}

TEST(LawKernels, OgdenEqualsTheScalarLawOnRandomDeformations) {
  std::mt19937 rng(3);
  for (int terms = 1; terms <= 3; ++terms)
    for (bool anp : {false, true}) {
      Batch b(random_deformations(rng, 61), rng);
      EXPECT_LT(worst_error(ogden(terms), b, anp, false), 1e-12) << terms << " terms, anp " << anp;
    }
}

TEST(LawKernels, OgdenEqualsTheScalarLawAtRepeatedAndNearlyRepeatedStretches) {
  std::mt19937 rng(4);
  for (int terms = 1; terms <= 3; ++terms)
    for (bool anp : {false, true}) {
      Batch b(near_repeated_deformations(rng), rng);
      EXPECT_LT(worst_error(ogden(terms), b, anp, false), 1e-12) << terms << " terms, anp " << anp;
    }
}

TEST(LawKernels, OgdenWithAlphaTwoIsTheDecoupledNeoHookeanKernel) {
  std::mt19937 rng(5);
  Batch b(random_deformations(rng, 61), rng);
  Batch ref = b;
  double min_j = 1e300;
  fem::kernels::tled_forces(ogden(1), b.view(), b.u.data(), 0, b.n, b.scratch.data(), min_j);
  fem::kernels::tled_forces(kNH, ref.view(), ref.u.data(), 0, ref.n, ref.scratch.data(), min_j);
  for (int e = 0; e < b.n; ++e) {
    if (b.F[e].determinant() <= 0) continue;  // the neo-Hookean kernel is not zeroed there
    double worst = 0, scale = 0;
    for (int i = 0; i < 12; ++i) {
      worst = std::max(worst, std::abs(b.out[i * b.n + e] - ref.out[i * b.n + e]));
      scale = std::max(scale, std::abs(ref.out[i * b.n + e]));
    }
    EXPECT_LE(worst, 1e-12 * scale) << "element " << e;
  }
}

TEST(LawKernels, ClosedFormPrincipalValuesMatchEigensSolver) {
  std::mt19937 rng(6);
  for (const Eigen::Matrix3d& F : near_repeated_deformations(rng)) {
    const Eigen::Matrix3d C = F.transpose() * F;
    const double c6[6] = {C(0, 0), C(1, 1), C(2, 2), C(0, 1), C(1, 2), C(0, 2)};
    const fem::kernels::PrincipalValues pv = fem::kernels::principal_values(c6);
    Eigen::Vector3d mine(pv.c[0], pv.c[1], pv.c[2]);
    std::sort(mine.data(), mine.data() + 3);
    const Eigen::Vector3d ref = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvalues();
    EXPECT_LT((mine - ref).cwiseAbs().maxCoeff(), 4e-15 * C.norm());
    const Eigen::Vector3d n(pv.n[0], pv.n[1], pv.n[2]);
    EXPECT_NEAR(n.norm(), 1.0, 1e-14);
    // N belongs to c_s: |C N − c_s N| within round-off of the gap to the nearest other value.
    const double gap = std::min(std::abs(pv.c[0] - pv.c[1]), std::abs(pv.c[0] - pv.c[2]));
    if (gap > 1e-6) EXPECT_LT((C * n - pv.c[0] * n).norm(), 1e-13 * C.norm());
  }
}

TEST(LawKernels, VectorPowMatchesStdPow) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> lx(-3.0, 3.0), ly(-10.0, 10.0);
  for (int i = 0; i < 20000; ++i) {
    const double x = std::exp(lx(rng)), y = ly(rng);
    EXPECT_NEAR(fem::vector_pow(x, y), std::pow(x, y), 4e-15 * std::pow(x, y)) << x << "^" << y;
  }
  for (double x : {1.0, 0.5, 2.0, std::sqrt(0.5), std::sqrt(2.0), 1e-300, 1e300})
    EXPECT_NEAR(fem::vector_log(x), std::log(x), 1e-15 * std::max(1.0, std::abs(std::log(x))));
}

// A Prony series on each base with an invariant form: the fused kernel's forces and internal
// variables against the law's relaxed_first_piola element by element (material/viscoelastic.hpp);
// an inverted element keeps its state.
TEST(LawKernels, FusedPronyUpdateEqualsTheScalarRecursion) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  const std::vector<ElasticLaw> bases = {
      kNH, MooneyRivlin{0.35 * kNH.mu, 0.15 * kNH.mu, kNH.bulk},
      TransverselyIsotropic{kNH.mu, 2.0 * kNH.mu, kNH.bulk, Eigen::Vector3d(0, 0.6, 0.8)}};
  for (const ElasticLaw& base : bases)
    for (int terms : {1, 4})
      for (bool anp : {false, true}) {
        Viscoelastic v;
        v.base = base;
        v.terms = terms;
        v.g = {0.3, 0.2, 0.1, 0.05};
        v.tau = {0.01, 0.1, 0.002, 1.0};
        const double dt = 1e-3;
        Batch b(random_deformations(rng, 29), rng);
        std::vector<double> in(6 * terms * b.n), out(6 * terms * b.n, -7.0);
        for (double& x : in) x = 300.0 * d(rng);
        fem::kernels::LawData data;
        data.state_in = in.data(), data.state_out = out.data(), data.stride = b.n, data.dt = dt;
        const bool fibres = fibre_of(base) != nullptr;
        if (fibres)
          for (int c = 0; c < 3; ++c) data.fibre[c] = b.fibre[c].data();
        const Viscoelastic law = anp ? isochoric_part(v) : v;
        double min_j = 1e300;
        if (anp)
          fem::kernels::anp_forces(law, b.view(), b.u.data(), 0, b.n, b.pressure.data(), b.scratch.data(), min_j, data);
        else
          fem::kernels::tled_forces(law, b.view(), b.u.data(), 0, b.n, b.scratch.data(), min_j, data);
        for (int e = 0; e < b.n; ++e) {
          Viscoelastic l = law;
          PronyStep step = prony_step(law, dt);
          if (fibres) set_fibre(l, step, Eigen::Vector3d(b.fibre[0][e], b.fibre[1][e], b.fibre[2][e]));
          double si[24], so[24];
          for (int c = 0; c < 6 * terms; ++c) so[c] = si[c] = in[c * b.n + e];
          const Eigen::Matrix3d& F = b.F[e];
          Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
          double stress = kStressScale;
          if (F.determinant() > 0) {
            P = relaxed_first_piola(l, step, F, si, so);
            stress += P.norm();
            if (anp) {
              const Eigen::Matrix3d pressure = b.mean_pressure(e) * F.determinant() * F.inverse().transpose();
              P += pressure;
              stress += pressure.norm();
            }
          }
          EXPECT_LT(b.error(e, P, stress), 1e-12) << law_name(v) << " terms " << terms << " anp " << anp << " element " << e;
          double scale = 0, worst = 0;
          for (int c = 0; c < 6 * terms; ++c) {
            scale = std::max(scale, std::abs(so[c]));
            worst = std::max(worst, std::abs(out[c * b.n + e] - so[c]));
          }
          EXPECT_LE(worst, 1e-12 * scale) << law_name(v) << " state, element " << e;
        }
      }
}
