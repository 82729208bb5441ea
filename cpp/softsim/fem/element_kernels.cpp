#include "softsim/fem/element_kernels.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "softsim/fem/cube_root.hpp"
#include "softsim/fem/kernel_macros.hpp"
#include "softsim/material/polar_decomposition.hpp"

#if defined(SOFTSIM_HAVE_OPENMP)
#define SOFTSIM_SIMD _Pragma("omp simd")
#define SOFTSIM_SIMD_MIN _Pragma("omp simd reduction(min : jmin)")
#define SOFTSIM_SIMD_MINMAX _Pragma("omp simd reduction(min : jmin) reduction(max : jmax)")
#define SOFTSIM_SIMD_MIN_WORST _Pragma("omp simd reduction(min : jmin) reduction(max : worst)")
#else
#define SOFTSIM_SIMD
#define SOFTSIM_SIMD_MIN
#define SOFTSIM_SIMD_MINMAX
#define SOFTSIM_SIMD_MIN_WORST
#endif

namespace softsim::fem::kernels {

// Small-strain element: ⁰V σ(ε) ∇N with ε = sym H (000 eqs. 9–12). Linear in u: the same as
// the precomputed 12 × 12 block Kₑ times the corner displacements, without storing Kₑ.
void linear_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu, double lambda) {
  SOFTSIM_SIMD
  for (int k = begin; k < end; ++k) {
    SOFTSIM_LOAD_H(s, u, k)
    const double V = s.vol[k];
    const double vmu = V * mu;
    const double vl_tr = V * lambda * (h00 + h11 + h22);
    const double s00 = 2.0 * vmu * h00 + vl_tr, s11 = 2.0 * vmu * h11 + vl_tr, s22 = 2.0 * vmu * h22 + vl_tr;
    const double s01 = vmu * (h01 + h10), s02 = vmu * (h02 + h20), s12 = vmu * (h12 + h21);
    SOFTSIM_STORE_FORCES(s, k, s00, s01, s02, s01, s11, s12, s02, s12, s22)
  }
}

// TLED, paper form: S = μ(I − C⁻¹) + λJ(J − 1)C⁻¹ (000 eq. 14), used as P = F S
// = μ F + (λ(J − 1) − μ/J) cof F, and nodal forces ⁰V P ∇N (= ⁰V B_Lᵀ Ŝ of 000 eq. 13).
// kAveraged (ANP): the volumetric pressure λ(J − 1) becomes the mean of the corners' nodal ones.
namespace {

template <bool kAveraged>
void paper_form_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu, double lambda,
                       const double* __restrict pressure, double& min_j) {
  double jmin = min_j;
  SOFTSIM_SIMD_MIN
  for (int k = begin; k < end; ++k) {
    SOFTSIM_LOAD_H(s, u, k)
    SOFTSIM_F_AND_COFACTOR
    jmin = std::min(jmin, J);
    const double p = kAveraged ? 0.25 * (pressure[a0] + pressure[a1] + pressure[a2] + pressure[a3])
                               : lambda * (J - 1.0);
    const double V = s.vol[k];
    const double cf = V * mu;
    const double cc = V * (p - mu / J);
    SOFTSIM_STORE_FORCES(s, k, cf * f00 + cc * c00, cf * f01 + cc * c01, cf * f02 + cc * c02,
                         cf * f10 + cc * c10, cf * f11 + cc * c11, cf * f12 + cc * c12,
                         cf * f20 + cc * c20, cf * f21 + cc * c21, cf * f22 + cc * c22)
  }
  min_j = jmin;
}

}  // namespace

void tled_paper_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu,
                       double lambda, double& min_j) {
  paper_form_kernel<false>(s, u, begin, end, mu, lambda, nullptr, min_j);
}

void anp_paper_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu,
                      const double* __restrict pressure, double& min_j) {
  paper_form_kernel<true>(s, u, begin, end, mu, 0.0, pressure, min_j);
}

void volume_ratio_kernel(const SoaView s, const double* __restrict u, int begin, int end,
                         double* __restrict volume_ratio, double& min_j) {
  double jmin = min_j;
  SOFTSIM_SIMD_MIN
  for (int k = begin; k < end; ++k) {
    SOFTSIM_LOAD_H(s, u, k)
    const double J = (1.0 + h00) * ((1.0 + h11) * (1.0 + h22) - h12 * h21) -
                     h01 * (h10 * (1.0 + h22) - h12 * h20) + h02 * (h10 * h21 - (1.0 + h11) * h20);
    volume_ratio[k] = J;
    jmin = std::min(jmin, J);
  }
  min_j = jmin;
}

// TLED, decoupled form (Miller et al. 2007): S = μJ^(−2/3)(I − I₁/3 C⁻¹) + KJ(J − 1)C⁻¹, as
// P = μ J^(−2/3) F + (K(J − 1) − μ J^(−2/3) I₁ / (3J)) cof F. kAveraged (ANP): K(J − 1) becomes
// the mean of the corners' nodal pressures.
namespace {

template <bool kExactRoot, bool kAveraged>
void tled_decoupled_body(const SoaView& s, const double* __restrict u, int k, double mu, double bulk,
                         const double* __restrict pressure, double& J_out) {
  SOFTSIM_LOAD_H(s, u, k)
  SOFTSIM_F_AND_COFACTOR
  J_out = J;
  const double x = kExactRoot ? 1.0 / std::cbrt(J) : inv_cbrt_newton(J);  // J^(−1/3)
  const double a = x * x;                                                   // J^(−2/3)
  const double inv_j = kExactRoot ? 1.0 / J : a * x;
  const double I1 = f00 * f00 + f01 * f01 + f02 * f02 + f10 * f10 + f11 * f11 + f12 * f12 +
                    f20 * f20 + f21 * f21 + f22 * f22;
  const double p = kAveraged ? 0.25 * (pressure[a0] + pressure[a1] + pressure[a2] + pressure[a3])
                             : bulk * (J - 1.0);
  const double V = s.vol[k];
  const double cf = V * mu * a;
  const double cc = V * (p - mu * a * I1 * inv_j * (1.0 / 3.0));
  SOFTSIM_STORE_FORCES(s, k, cf * f00 + cc * c00, cf * f01 + cc * c01, cf * f02 + cc * c02,
                       cf * f10 + cc * c10, cf * f11 + cc * c11, cf * f12 + cc * c12,
                       cf * f20 + cc * c20, cf * f21 + cc * c21, cf * f22 + cc * c22)
}

template <bool kAveraged>
void decoupled_form_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu,
                           double bulk, const double* __restrict pressure, double* __restrict volume_ratio,
                           double& min_j) {
  double jmin = 1e300, jmax = -1e300;  // of this range only: they decide on the re-scan below
  SOFTSIM_SIMD_MINMAX
  for (int k = begin; k < end; ++k) {
    double J;
    tled_decoupled_body<false, kAveraged>(s, u, k, mu, bulk, pressure, J);
    volume_ratio[k] = J;
    jmin = std::min(jmin, J);
    jmax = std::max(jmax, J);
  }
  // Elements whose J lies outside the range where the Newton root is exact are recomputed
  // with the library root; the choice depends on the element alone, so it is deterministic.
  if (jmin < kInvCbrtMinJ || jmax > kInvCbrtMaxJ) {
    for (int k = begin; k < end; ++k) {
      const double J = volume_ratio[k];  // as the vectorised loop saw it
      if (J > 0 && (J < kInvCbrtMinJ || J > kInvCbrtMaxJ)) {
        double unused;
        tled_decoupled_body<true, kAveraged>(s, u, k, mu, bulk, pressure, unused);
      }
    }
  }
  min_j = std::min(min_j, jmin);
}

}  // namespace

void tled_decoupled_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu,
                           double bulk, double* __restrict volume_ratio, double& min_j) {
  decoupled_form_kernel<false>(s, u, begin, end, mu, bulk, nullptr, volume_ratio, min_j);
}

void anp_decoupled_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu,
                          const double* __restrict pressure, double* __restrict volume_ratio, double& min_j) {
  decoupled_form_kernel<true>(s, u, begin, end, mu, 0.0, pressure, volume_ratio, min_j);
}

namespace {

// Corotational: F = R S, forces R Kₑ (Rᵀx − X) = ⁰V R σ(S − I) ∇N (see material/small_strain.hpp),
// one element at a time with the library's polar decomposition (material::polar_decomposition:
// Frobenius-norm scaled Newton iterated to convergence).
// An inverted element (J ≤ 0) gets zero forces here; the caller's min_j reports it.
void corotational_exact(const SoaView& s, const double* __restrict u, int k, double mu, double lambda) {
  SOFTSIM_LOAD_H(s, u, k)
  SOFTSIM_F_AND_COFACTOR
  (void)c10, (void)c11, (void)c12, (void)c20, (void)c21, (void)c22;
  double m[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  if (J > 0) {
    Eigen::Matrix3d F;
    F << f00, f01, f02, f10, f11, f12, f20, f21, f22;
    const material::Polar p = material::polar_decomposition(F);
    const double e00 = p.S(0, 0) - 1.0, e11 = p.S(1, 1) - 1.0, e22 = p.S(2, 2) - 1.0;
    const double V = s.vol[k];
    const double tr = lambda * (e00 + e11 + e22);
    Eigen::Matrix3d sig;
    sig << 2.0 * mu * e00 + tr, 2.0 * mu * p.S(0, 1), 2.0 * mu * p.S(0, 2),  //
        2.0 * mu * p.S(1, 0), 2.0 * mu * e11 + tr, 2.0 * mu * p.S(1, 2),     //
        2.0 * mu * p.S(2, 0), 2.0 * mu * p.S(2, 1), 2.0 * mu * e22 + tr;
    const Eigen::Matrix3d P = V * (p.R * sig);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[3 * i + j] = P(i, j);
  }
  SOFTSIM_STORE_FORCES(s, k, m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8])
}

// The same, vectorised: always kPolarIterations Newton iterations (no early exit, so the loop
// vectorises; enough for strains of a few tens of per cent). Each element's squared last update
// is compared with kPolarConverged and a 0/1 flag stored in `last_update` (0: converged and not
// inverted); if any element of the range is flagged, the flagged ones are recomputed by
// corotational_exact after the loop. The choice is made from the stored flag of that element
// alone, so it is deterministic whatever the split into threads.
constexpr int kPolarIterations = 6;
constexpr double kPolarConverged = 1e-20;  // squared size of the last update

}  // namespace

void corotational_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu,
                         double lambda, double* __restrict last_update, double& min_j) {
  double jmin = min_j, worst = 0.0;
  SOFTSIM_SIMD_MIN_WORST
  for (int k = begin; k < end; ++k) {
    SOFTSIM_LOAD_H(s, u, k)
    SOFTSIM_F_AND_COFACTOR
    (void)c10, (void)c11, (void)c12, (void)c20, (void)c21, (void)c22;
    jmin = std::min(jmin, J);
    // Newton iteration X ← (γ X + X⁻ᵀ/γ)/2 from X = F, kPolarIterations times. Determinant scaling
    // γ = |det X|^(−1/3) (Byers & Xu) in the first iteration and as long as the previous squared
    // update was ≥ 1e-4, γ = 1 (plain Newton, quadratic convergence) once it is below; no library
    // call, so the loop vectorises.
    double x00 = f00, x01 = f01, x02 = f02, x10 = f10, x11 = f11, x12 = f12, x20 = f20, x21 = f21, x22 = f22;
    double change = 1.0;
#pragma GCC unroll 8
    for (int it = 0; it < kPolarIterations; ++it) {
      const double y00 = x11 * x22 - x12 * x21, y01 = x12 * x20 - x10 * x22, y02 = x10 * x21 - x11 * x20;
      const double y10 = x02 * x21 - x01 * x22, y11 = x00 * x22 - x02 * x20, y12 = x01 * x20 - x00 * x21;
      const double y20 = x01 * x12 - x02 * x11, y21 = x02 * x10 - x00 * x12, y22 = x00 * x11 - x01 * x10;
      const double det = x00 * y00 + x01 * y01 + x02 * y02;
      const double inv = 1.0 / det;
      const double g = change < 1e-4 ? 1.0 : inv_cbrt_newton(std::abs(det));
      const double a = 0.5 * g, b = 0.5 * inv / g;
      const double n00 = a * x00 + b * y00, n01 = a * x01 + b * y01, n02 = a * x02 + b * y02;
      const double n10 = a * x10 + b * y10, n11 = a * x11 + b * y11, n12 = a * x12 + b * y12;
      const double n20 = a * x20 + b * y20, n21 = a * x21 + b * y21, n22 = a * x22 + b * y22;
      change = (n00 - x00) * (n00 - x00) + (n01 - x01) * (n01 - x01) + (n02 - x02) * (n02 - x02) +
               (n10 - x10) * (n10 - x10) + (n11 - x11) * (n11 - x11) + (n12 - x12) * (n12 - x12) +
               (n20 - x20) * (n20 - x20) + (n21 - x21) * (n21 - x21) + (n22 - x22) * (n22 - x22);
      x00 = n00, x01 = n01, x02 = n02, x10 = n10, x11 = n11, x12 = n12, x20 = n20, x21 = n21, x22 = n22;
    }
    // 0 = converged; anything else (not converged, inverted, or NaN from a degenerate iterate,
    // which max() would silently drop) sends the element to the exact path.
    const double flag = J > 0 && change <= kPolarConverged ? 0.0 : 1.0;
    last_update[k] = flag;
    worst = std::max(worst, flag);
    // S = Rᵀ F (symmetrised); s00 … s12 hold the entries of S − I. σ = 2μ (S − I) + λ tr(S − I) I,
    // ⁰V P = ⁰V R σ.
    const double s00 = x00 * f00 + x10 * f10 + x20 * f20 - 1.0;
    const double s11 = x01 * f01 + x11 * f11 + x21 * f21 - 1.0;
    const double s22 = x02 * f02 + x12 * f12 + x22 * f22 - 1.0;
    const double s01 = 0.5 * ((x00 * f01 + x10 * f11 + x20 * f21) + (x01 * f00 + x11 * f10 + x21 * f20));
    const double s02 = 0.5 * ((x00 * f02 + x10 * f12 + x20 * f22) + (x02 * f00 + x12 * f10 + x22 * f20));
    const double s12 = 0.5 * ((x01 * f02 + x11 * f12 + x21 * f22) + (x02 * f01 + x12 * f11 + x22 * f21));
    const double V = s.vol[k];
    const double vmu2 = 2.0 * V * mu, vl_tr = V * lambda * (s00 + s11 + s22);
    const double t00 = vmu2 * s00 + vl_tr, t11 = vmu2 * s11 + vl_tr, t22 = vmu2 * s22 + vl_tr;
    const double t01 = vmu2 * s01, t02 = vmu2 * s02, t12 = vmu2 * s12;
    SOFTSIM_STORE_FORCES(s, k, x00 * t00 + x01 * t01 + x02 * t02, x00 * t01 + x01 * t11 + x02 * t12,
                         x00 * t02 + x01 * t12 + x02 * t22, x10 * t00 + x11 * t01 + x12 * t02,
                         x10 * t01 + x11 * t11 + x12 * t12, x10 * t02 + x11 * t12 + x12 * t22,
                         x20 * t00 + x21 * t01 + x22 * t02, x20 * t01 + x21 * t11 + x22 * t12,
                         x20 * t02 + x21 * t12 + x22 * t22)
  }
  if (!(worst <= kPolarConverged))
    for (int k = begin; k < end; ++k)
      if (!(last_update[k] <= kPolarConverged)) corotational_exact(s, u, k, mu, lambda);
  min_j = jmin;
}

}  // namespace softsim::fem::kernels
