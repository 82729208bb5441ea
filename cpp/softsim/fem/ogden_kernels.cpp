#include "softsim/fem/ogden_kernels.hpp"

#include <algorithm>
#include <cmath>

#include "softsim/fem/kernel_macros.hpp"
#include "softsim/fem/root_fixup_pass.hpp"
#include "softsim/fem/vector_pow.hpp"

namespace softsim::fem::kernels {

namespace {

// Steps 1–3 of the header: c_s with its eigenvector (nx, ny, nz), m and E (e00 … e02), h.
struct Principal {
  double cs, nx, ny, nz, m, e00, e11, e22, e01, e12, e02, h;
};

[[gnu::always_inline]] inline Principal principal(double C00, double C11, double C22, double C01, double C12,
                                                  double C02) {
  Principal r;
  const double q = (C00 + C11 + C22) * (1.0 / 3.0);
  const double B00 = C00 - q, B11 = C11 - q, B22 = C22 - q;
  const double p2 = (B00 * B00 + B11 * B11 + B22 * B22 + 2.0 * (C01 * C01 + C02 * C02 + C12 * C12)) * (1.0 / 6.0);
  const double p = std::sqrt(p2);
  const double ip = p > 1e-150 ? 1.0 / p : 0.0;
  const double detB = B00 * (B11 * B22 - C12 * C12) - C01 * (C01 * B22 - C12 * C02) + C02 * (C01 * C12 - B11 * C02);
  const double rr = 0.5 * detB * ip * ip * ip;
  const double ar = std::min(std::abs(rr), 1.0);
  // Start from a quartic fit of the root over |r| ∈ [0, 1] (within 1.9e-5 of it); Newton's error
  // then falls as e ← 0.87 e² (below 1e-19 after two steps).
  double beta = 1.7320689482165845 +
                ar * (0.33275175023951165 + ar * (-0.09171204015006557 + ar * (0.035006397978561504 -
                                                                                  ar * 0.008128714465262922)));
#pragma GCC unroll 2
  for (int it = 0; it < 2; ++it) beta -= (beta * beta * beta - 3.0 * beta - 2.0 * ar) / (3.0 * beta * beta - 3.0);
  r.cs = q + p * (rr >= 0 ? beta : -beta);
  // Eigenvector: the largest cross product of two rows of C − c_s I.
  const double m00 = C00 - r.cs, m11 = C11 - r.cs, m22 = C22 - r.cs;
  const double xa = C01 * C12 - C02 * m11, ya = C02 * C01 - m00 * C12, za = m00 * m11 - C01 * C01;  // row0 × row1
  const double xb = C01 * m22 - C02 * C12, yb = C02 * C02 - m00 * m22, zb = m00 * C12 - C01 * C02;  // row0 × row2
  const double xc = m11 * m22 - C12 * C12, yc = C12 * C02 - C01 * m22, zc = C01 * C12 - m11 * C02;  // row1 × row2
  const double na = xa * xa + ya * ya + za * za, nb = xb * xb + yb * yb + zb * zb, nc = xc * xc + yc * yc + zc * zc;
  const bool pick_a = na >= nb && na >= nc, pick_b = !pick_a && nb >= nc;
  const double vx = pick_a ? xa : (pick_b ? xb : xc), vy = pick_a ? ya : (pick_b ? yb : yc);
  const double vz = pick_a ? za : (pick_b ? zb : zc), nv = pick_a ? na : (pick_b ? nb : nc);
  const bool found = nv > 1e-300;
  const double in = found ? 1.0 / std::sqrt(nv) : 0.0;
  r.nx = found ? vx * in : 1.0, r.ny = vy * in, r.nz = vz * in;
  // The plane part less its mean.
  r.m = 0.5 * (C00 + C11 + C22 - r.cs);
  const double d = r.cs - r.m;
  r.e00 = C00 - r.m - d * r.nx * r.nx, r.e11 = C11 - r.m - d * r.ny * r.ny, r.e22 = C22 - r.m - d * r.nz * r.nz;
  r.e01 = C01 - d * r.nx * r.ny, r.e12 = C12 - d * r.ny * r.nz, r.e02 = C02 - d * r.nx * r.nz;
  r.h = std::sqrt(0.5 * (r.e00 * r.e00 + r.e11 * r.e11 + r.e22 * r.e22 +
                         2.0 * (r.e01 * r.e01 + r.e12 * r.e12 + r.e02 * r.e02)));
  return r;
}

template <int kTerms, bool kAveraged>
struct OgdenBody {
  SoaView s;
  const double* __restrict u;
  const double* __restrict pressure;
  double mu[3], half_alpha[3], bulk;

  template <bool kExactRoot>
  [[gnu::always_inline]] inline double element(int k) const {
    SOFTSIM_LOAD_H(s, u, k)
    SOFTSIM_F_AND_COFACTOR
    const double x = inv_cbrt<kExactRoot>(J);
    const double b = x * x;  // J^(−2/3): c̄_i = b c_i = λ̄_i²
    const double inv_j = kExactRoot ? 1.0 / J : b * x;
    const double C00 = f00 * f00 + f10 * f10 + f20 * f20, C11 = f01 * f01 + f11 * f11 + f21 * f21;
    const double C22 = f02 * f02 + f12 * f12 + f22 * f22, C01 = f00 * f01 + f10 * f11 + f20 * f21;
    const double C12 = f01 * f02 + f11 * f12 + f21 * f22, C02 = f00 * f02 + f10 * f12 + f20 * f22;
    const Principal pv = principal(C00, C11, C22, C01, C12, C02);
    const double cp = pv.m + pv.h, cm = pv.m - pv.h;
    // β_i = Σ_p μ_p (λ̄_i^α_p − ⅓ Σ_k λ̄_k^α_p) (material/ogden.hpp).
    const bool ok = J > 0;
    const double ls = ok ? b * pv.cs : 1.0, lp = ok ? b * cp : 1.0, lm = ok ? b * cm : 1.0;
    // ln λ̄_i² once, then λ̄_i^α_p = exp(α_p/2 ln λ̄_i²) per term.
    const double gs = vector_log(ls), gp = vector_log(lp), gm = vector_log(lm);
    double bs = 0, bp = 0, bm = 0;
#pragma GCC unroll 3
    for (int t = 0; t < kTerms; ++t) {
      const double ws = vector_exp(half_alpha[t] * gs), wp = vector_exp(half_alpha[t] * gp);
      const double wm = vector_exp(half_alpha[t] * gm);
      const double mean = (ws + wp + wm) * (1.0 / 3.0);
      bs += mu[t] * (ws - mean), bp += mu[t] * (wp - mean), bm += mu[t] * (wm - mean);
    }
    // s_i = β_i / c_i without a division: c_s c₊ c₋ = det C = J².
    const double j2 = inv_j * inv_j;
    const double ss = bs * cp * cm * j2, sp = bp * pv.cs * cm * j2, sm = bm * pv.cs * cp * j2;
    const double sbar = 0.5 * (sp + sm);
    const double g = pv.h > 1e-150 ? (sp - sm) / (2.0 * pv.h) : 0.0;
    const double dn = ss - sbar;
    const double S00 = sbar + dn * pv.nx * pv.nx + g * pv.e00, S11 = sbar + dn * pv.ny * pv.ny + g * pv.e11;
    const double S22 = sbar + dn * pv.nz * pv.nz + g * pv.e22, S01 = dn * pv.nx * pv.ny + g * pv.e01;
    const double S12 = dn * pv.ny * pv.nz + g * pv.e12, S02 = dn * pv.nx * pv.nz + g * pv.e02;
    const double p = kAveraged ? 0.25 * (pressure[a0] + pressure[a1] + pressure[a2] + pressure[a3]) : bulk * (J - 1.0);
    const double V = ok ? s.vol[k] : 0.0;
    const double m00 = f00 * S00 + f01 * S01 + f02 * S02 + p * c00, m01 = f00 * S01 + f01 * S11 + f02 * S12 + p * c01;
    const double m02 = f00 * S02 + f01 * S12 + f02 * S22 + p * c02, m10 = f10 * S00 + f11 * S01 + f12 * S02 + p * c10;
    const double m11 = f10 * S01 + f11 * S11 + f12 * S12 + p * c11, m12 = f10 * S02 + f11 * S12 + f12 * S22 + p * c12;
    const double m20 = f20 * S00 + f21 * S01 + f22 * S02 + p * c20, m21 = f20 * S01 + f21 * S11 + f22 * S12 + p * c21;
    const double m22 = f20 * S02 + f21 * S12 + f22 * S22 + p * c22;
    SOFTSIM_STORE_FORCES(s, k, ok ? V * m00 : 0.0, ok ? V * m01 : 0.0, ok ? V * m02 : 0.0, ok ? V * m10 : 0.0,
                         ok ? V * m11 : 0.0, ok ? V * m12 : 0.0, ok ? V * m20 : 0.0, ok ? V * m21 : 0.0,
                         ok ? V * m22 : 0.0)
    return J;
  }
};

template <int kTerms>
void run(const material::Ogden& law, const SoaView& s, const double* __restrict u, int begin, int end,
         const double* __restrict pressure, double* __restrict scratch, double& min_j) {
  const double mu[3] = {law.mu[0], law.mu[1], law.mu[2]};
  const double half_alpha[3] = {0.5 * law.alpha[0], 0.5 * law.alpha[1], 0.5 * law.alpha[2]};
  if (pressure) {
    const OgdenBody<kTerms, true> body{s, u, pressure, {mu[0], mu[1], mu[2]},
                                       {half_alpha[0], half_alpha[1], half_alpha[2]}, law.bulk};
    root_fixup_pass(body, begin, end, scratch, min_j);
  } else {
    const OgdenBody<kTerms, false> body{s, u, pressure, {mu[0], mu[1], mu[2]},
                                        {half_alpha[0], half_alpha[1], half_alpha[2]}, law.bulk};
    root_fixup_pass(body, begin, end, scratch, min_j);
  }
}

}  // namespace

void ogden_forces(const material::Ogden& law, const SoaView s, const double* __restrict u, int begin, int end,
                  const double* __restrict pressure, double* __restrict scratch, double& min_j) {
  switch (law.terms) {
    case 1: return run<1>(law, s, u, begin, end, pressure, scratch, min_j);
    case 2: return run<2>(law, s, u, begin, end, pressure, scratch, min_j);
    default: return run<3>(law, s, u, begin, end, pressure, scratch, min_j);
  }
}

PrincipalValues principal_values(const double C[6]) {
  const Principal p = principal(C[0], C[1], C[2], C[3], C[4], C[5]);
  return {{p.cs, p.m + p.h, p.m - p.h}, {p.nx, p.ny, p.nz}};
}

}  // namespace softsim::fem::kernels
