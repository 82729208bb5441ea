#include "softsim/fem/invariant_kernels.hpp"

#include <cstddef>

#include "softsim/fem/kernel_macros.hpp"
#include "softsim/fem/root_fixup_pass.hpp"

namespace softsim::fem::kernels {

namespace {

enum class Fibre { none, law, element };

template <bool kC01, Fibre kFibre, int kTerms, bool kAveraged>
struct InvariantBody {
  SoaView s;
  const double* __restrict u;
  const double* __restrict pressure;
  InvariantLaw law;
  PronyTerms prony;
  LawData d;

  template <bool kExactRoot>
  [[gnu::always_inline]] inline double element(int k) const {
    SOFTSIM_LOAD_H(s, u, k)
    SOFTSIM_F_AND_COFACTOR
    const double x = inv_cbrt<kExactRoot>(J);  // J^(−1/3)
    const double b = x * x;                    // J^(−2/3)
    const double inv_j = kExactRoot ? 1.0 / J : b * x;
    const double I1 = f00 * f00 + f01 * f01 + f02 * f02 + f10 * f10 + f11 * f11 + f12 * f12 + f20 * f20 +
                      f21 * f21 + f22 * f22;
    double gI = law.m1 * b, gC = 0.0, gInv = law.m1 * b * I1, gA = 0.0;
    // Mooney–Rivlin: F C = (F Fᵀ) F, tr C² = |F Fᵀ|², I₂ = ½ (I₁² − tr C²).
    double fc00 = 0, fc01 = 0, fc02 = 0, fc10 = 0, fc11 = 0, fc12 = 0, fc20 = 0, fc21 = 0, fc22 = 0;
    if constexpr (kC01) {
      const double l00 = f00 * f00 + f01 * f01 + f02 * f02, l11 = f10 * f10 + f11 * f11 + f12 * f12;
      const double l22 = f20 * f20 + f21 * f21 + f22 * f22, l01 = f00 * f10 + f01 * f11 + f02 * f12;
      const double l02 = f00 * f20 + f01 * f21 + f02 * f22, l12 = f10 * f20 + f11 * f21 + f12 * f22;
      const double trC2 = l00 * l00 + l11 * l11 + l22 * l22 + 2.0 * (l01 * l01 + l02 * l02 + l12 * l12);
      const double I2 = 0.5 * (I1 * I1 - trC2);
      const double m2b2 = law.m2 * b * b;
      gI += m2b2 * I1;
      gC = -m2b2;
      gInv += 2.0 * m2b2 * I2;
      fc00 = l00 * f00 + l01 * f10 + l02 * f20, fc01 = l00 * f01 + l01 * f11 + l02 * f21;
      fc02 = l00 * f02 + l01 * f12 + l02 * f22, fc10 = l01 * f00 + l11 * f10 + l12 * f20;
      fc11 = l01 * f01 + l11 * f11 + l12 * f21, fc12 = l01 * f02 + l11 * f12 + l12 * f22;
      fc20 = l02 * f00 + l12 * f10 + l22 * f20, fc21 = l02 * f01 + l12 * f11 + l22 * f21;
      fc22 = l02 * f02 + l12 * f12 + l22 * f22;
    }
    // Fibre: F a, I₄ = |F a|², φ = 2η (b I₄ − 1) b.
    double ax = 0, ay = 0, az = 0, fax = 0, fay = 0, faz = 0;
    if constexpr (kFibre != Fibre::none) {
      ax = kFibre == Fibre::element ? d.fibre[0][k] : law.fibre[0];
      ay = kFibre == Fibre::element ? d.fibre[1][k] : law.fibre[1];
      az = kFibre == Fibre::element ? d.fibre[2][k] : law.fibre[2];
      fax = f00 * ax + f01 * ay + f02 * az, fay = f10 * ax + f11 * ay + f12 * az, faz = f20 * ax + f21 * ay + f22 * az;
      const double I4 = fax * fax + fay * fay + faz * faz;
      gA = 2.0 * law.eta * (b * I4 - 1.0) * b;
      gInv += gA * I4;
    }
    gInv *= -1.0 / 3.0;
    const bool ok = J > 0;
    const double p = kAveraged ? 0.25 * (pressure[a0] + pressure[a1] + pressure[a2] + pressure[a3]) : law.bulk * (J - 1.0);
    const double cc = gInv * inv_j + p;
    double m00 = gI * f00 + cc * c00, m01 = gI * f01 + cc * c01, m02 = gI * f02 + cc * c02;
    double m10 = gI * f10 + cc * c10, m11 = gI * f11 + cc * c11, m12 = gI * f12 + cc * c12;
    double m20 = gI * f20 + cc * c20, m21 = gI * f21 + cc * c21, m22 = gI * f22 + cc * c22;
    if constexpr (kC01) {
      m00 += gC * fc00, m01 += gC * fc01, m02 += gC * fc02, m10 += gC * fc10, m11 += gC * fc11;
      m12 += gC * fc12, m20 += gC * fc20, m21 += gC * fc21, m22 += gC * fc22;
    }
    if constexpr (kFibre != Fibre::none) {
      m00 += gA * fax * ax, m01 += gA * fax * ay, m02 += gA * fax * az;
      m10 += gA * fay * ax, m11 += gA * fay * ay, m12 += gA * fay * az;
      m20 += gA * faz * ax, m21 += gA * faz * ay, m22 += gA * faz * az;
    }
    if constexpr (kTerms > 0) {
      // S_iso (xx yy zz xy yz xz), C⁻¹ = cofᵀ cof / J², then Aᵢ ← eᵢ Aᵢ + gᵢ (1 − eᵢ) S_iso
      // (material/viscoelastic.hpp) and P −= F Σᵢ Aᵢ. An inverted element keeps its state.
      const double j2 = inv_j * inv_j;
      double s6[6] = {gI + gInv * j2 * (c00 * c00 + c10 * c10 + c20 * c20),
                      gI + gInv * j2 * (c01 * c01 + c11 * c11 + c21 * c21),
                      gI + gInv * j2 * (c02 * c02 + c12 * c12 + c22 * c22),
                      gInv * j2 * (c00 * c01 + c10 * c11 + c20 * c21),
                      gInv * j2 * (c01 * c02 + c11 * c12 + c21 * c22),
                      gInv * j2 * (c00 * c02 + c10 * c12 + c20 * c22)};
      if constexpr (kC01) {
        s6[0] += gC * (f00 * f00 + f10 * f10 + f20 * f20), s6[1] += gC * (f01 * f01 + f11 * f11 + f21 * f21);
        s6[2] += gC * (f02 * f02 + f12 * f12 + f22 * f22), s6[3] += gC * (f00 * f01 + f10 * f11 + f20 * f21);
        s6[4] += gC * (f01 * f02 + f11 * f12 + f21 * f22), s6[5] += gC * (f00 * f02 + f10 * f12 + f20 * f22);
      }
      if constexpr (kFibre != Fibre::none) {
        s6[0] += gA * ax * ax, s6[1] += gA * ay * ay, s6[2] += gA * az * az;
        s6[3] += gA * ax * ay, s6[4] += gA * ay * az, s6[5] += gA * ax * az;
      }
      double sum[6] = {0, 0, 0, 0, 0, 0};
#pragma GCC unroll 24
      for (int t = 0; t < kTerms; ++t)
#pragma GCC unroll 6
        for (int c = 0; c < 6; ++c) {
          const std::size_t at = static_cast<std::size_t>(6 * t + c) * d.stride + k;
          const double in = d.state_in[at];
          const double a = prony.decay[t] * in + prony.weight[t] * s6[c];
          d.state_out[at] = ok ? a : in;
          sum[c] += a;
        }
      // F Σ, Σ symmetric (xx yy zz xy yz xz).
      m00 -= f00 * sum[0] + f01 * sum[3] + f02 * sum[5], m01 -= f00 * sum[3] + f01 * sum[1] + f02 * sum[4];
      m02 -= f00 * sum[5] + f01 * sum[4] + f02 * sum[2], m10 -= f10 * sum[0] + f11 * sum[3] + f12 * sum[5];
      m11 -= f10 * sum[3] + f11 * sum[1] + f12 * sum[4], m12 -= f10 * sum[5] + f11 * sum[4] + f12 * sum[2];
      m20 -= f20 * sum[0] + f21 * sum[3] + f22 * sum[5], m21 -= f20 * sum[3] + f21 * sum[1] + f22 * sum[4];
      m22 -= f20 * sum[5] + f21 * sum[4] + f22 * sum[2];
    }
    const double V = s.vol[k];
    SOFTSIM_STORE_FORCES(s, k, ok ? V * m00 : 0.0, ok ? V * m01 : 0.0, ok ? V * m02 : 0.0, ok ? V * m10 : 0.0,
                         ok ? V * m11 : 0.0, ok ? V * m12 : 0.0, ok ? V * m20 : 0.0, ok ? V * m21 : 0.0,
                         ok ? V * m22 : 0.0)
    return J;
  }
};

template <bool kC01, Fibre kFibre, int kTerms>
void run(const InvariantLaw& law, const PronyTerms& prony, const SoaView& s, const double* __restrict u, int begin,
         int end, const double* __restrict pressure, const LawData& d, double* __restrict scratch, double& min_j) {
  if (pressure) {
    const InvariantBody<kC01, kFibre, kTerms, true> body{s, u, pressure, law, prony, d};
    root_fixup_pass(body, begin, end, scratch, min_j);
  } else {
    const InvariantBody<kC01, kFibre, kTerms, false> body{s, u, pressure, law, prony, d};
    root_fixup_pass(body, begin, end, scratch, min_j);
  }
}

template <bool kC01, Fibre kFibre>
void run_terms(const InvariantLaw& law, const PronyTerms& prony, const SoaView& s, const double* __restrict u,
               int begin, int end, const double* __restrict pressure, const LawData& d, double* __restrict scratch,
               double& min_j) {
  switch (prony.terms) {
    case 0: return run<kC01, kFibre, 0>(law, prony, s, u, begin, end, pressure, d, scratch, min_j);
    case 1: return run<kC01, kFibre, 1>(law, prony, s, u, begin, end, pressure, d, scratch, min_j);
    case 2: return run<kC01, kFibre, 2>(law, prony, s, u, begin, end, pressure, d, scratch, min_j);
    case 3: return run<kC01, kFibre, 3>(law, prony, s, u, begin, end, pressure, d, scratch, min_j);
    default: return run<kC01, kFibre, 4>(law, prony, s, u, begin, end, pressure, d, scratch, min_j);
  }
}

}  // namespace

void invariant_forces(const InvariantLaw& law, const PronyTerms& prony, const SoaView s, const double* __restrict u,
                      int begin, int end, const double* __restrict pressure, const LawData& data,
                      double* __restrict scratch, double& min_j) {
  // Mooney–Rivlin has no fibre and the fibre law no C01 term: four kinds, not six.
  if (law.has_c01) run_terms<true, Fibre::none>(law, prony, s, u, begin, end, pressure, data, scratch, min_j);
  else if (!law.has_fibre) run_terms<false, Fibre::none>(law, prony, s, u, begin, end, pressure, data, scratch, min_j);
  else if (data.fibre[0]) run_terms<false, Fibre::element>(law, prony, s, u, begin, end, pressure, data, scratch, min_j);
  else run_terms<false, Fibre::law>(law, prony, s, u, begin, end, pressure, data, scratch, min_j);
}

}  // namespace softsim::fem::kernels
