#pragma once
// The AVX2 kernel of one assembled linear row (linear_rows.hpp), for builds that target AVX2 and
// FMA but not AVX-512 (most desktop CPUs, AMD's before Zen 4). It consumes the non-AVX-512
// storage order of LinearStiffnessRows::kBlockSlot: a block's eight values as the two 4-wide
// halves (K_00 K_01 K_10 K_11) and (K_20 K_21 K_02 K_12), K_22 apart.
// Defines SOFTSIM_ROWS_AVX2 where the build targets AVX2 with FMA.
#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#define SOFTSIM_ROWS_AVX2 1

namespace softsim::fem::rows_avx2 {

// A block's two 4-wide halves and its K_22 as doubles, from double or single-precision storage.
inline __m256d load_half(const double* p) { return _mm256_load_pd(p); }
inline __m256d load_half(const float* p) { return _mm256_cvtps_pd(_mm_load_ps(p)); }
inline __m128d load_k22(const double* p) { return _mm_load_sd(p); }
inline __m128d load_k22(const float* p) { return _mm_set_sd(*p); }

// f[0..2] = Σ_p K_p u_{neighbour[p]} over the row's `count` blocks. A neighbour's displacement
// is read by two broadcast loads, (u0 u1 u0 u1) and (u2 u2 u2 u2), and one blend makes
// (u0 u1 u2 u2): the first half of the block multiplies the former, the second half the
// latter, and K_22 u2 is a scalar multiply-add. No lane-crossing shuffle (they are slow on AMD
// cores) and no read beyond u2, so the last node of the mesh needs no padding. Two blocks per
// iteration into two sets of accumulators (the multiply-add latency would otherwise bound the
// loop). The row's three sums are formed once at its end, from the lanes a of the first and b
// of the second half: f0 = a0 + a1 + b2, f1 = a2 + a3 + b3, f2 = b0 + b1 + K_22 u2. Forced
// inline: the caller's row loop must not pay a call per row. The stored values may be double or
// float (LinearPrecision); the arithmetic is in double precision either way.
template <class Value>
[[gnu::always_inline]] inline void row(const Value* block, const Value* k22, const int* neighbour, int count,
                                       const double* u, double* f) {
  __m256d a0 = _mm256_setzero_pd(), b0 = a0, a1 = a0, b1 = a0;
  __m128d c0 = _mm_setzero_pd(), c1 = c0;
  const auto add_block = [&](int p, __m256d& a, __m256d& b, __m128d& c) {
    const double* x = u + neighbour[p];
    const __m256d x01 = _mm256_broadcast_pd(reinterpret_cast<const __m128d*>(x));
    const __m256d x2 = _mm256_broadcast_sd(x + 2);
    a = _mm256_fmadd_pd(load_half(block + 8 * p), x01, a);
    b = _mm256_fmadd_pd(load_half(block + 8 * p + 4), _mm256_blend_pd(x01, x2, 0xC), b);
    c = _mm_fmadd_sd(load_k22(k22 + p), _mm256_castpd256_pd128(x2), c);
  };
  int p = 0;
  for (; p + 1 < count; p += 2) {
    add_block(p, a0, b0, c0);
    add_block(p + 1, a1, b1, c1);
  }
  if (p < count) add_block(p, a0, b0, c0);
  alignas(32) double a[4], b[4];
  _mm256_store_pd(a, _mm256_add_pd(a0, a1));
  _mm256_store_pd(b, _mm256_add_pd(b0, b1));
  f[0] = a[0] + a[1] + b[2];
  f[1] = a[2] + a[3] + b[3];
  f[2] = b[0] + b[1] + _mm_cvtsd_f64(_mm_add_sd(c0, c1));
}

}  // namespace softsim::fem::rows_avx2
#endif
