#pragma once
// The AVX-512 kernel of one assembled linear row (linear_rows.hpp), over double or (with
// LinearPrecision::single_precision) float stored values. It is templated on the type the block
// values are stored in; the arithmetic is in double precision either way.
// Defines SOFTSIM_ROWS_AVX512 where the build targets AVX-512 (with its 256-bit forms).
#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#define SOFTSIM_ROWS_AVX512 1

namespace softsim::fem::rows_avx512 {

// A block's first eight values (K_00 .. K_21, row by row) as eight doubles.
inline __m512d load_block(const double* p) { return _mm512_load_pd(p); }
inline __m512d load_block(const float* p) { return _mm512_cvtps_pd(_mm256_load_ps(p)); }
// A block's K_22 in all four lanes.
inline __m256d broadcast_k22(const double* p) { return _mm256_broadcast_sd(p); }
inline __m256d broadcast_k22(const float* p) { return _mm256_set1_pd(*p); }

// A row's three sums from its accumulator: (t0 + t1 + t2, t3 + t4 + t5, t6 + t7 + k), written
// with one masked store.
inline void store_row_sums(__m512d t, double k, double* f) {
  const __m512d kv = _mm512_castpd128_pd512(_mm_set_sd(k));
  const __m512d first = _mm512_permutexvar_pd(_mm512_set_epi64(0, 0, 0, 0, 0, 6, 3, 0), t);
  const __m512d second = _mm512_permutexvar_pd(_mm512_set_epi64(0, 0, 0, 0, 0, 7, 4, 1), t);
  const __m512d third = _mm512_permutex2var_pd(t, _mm512_set_epi64(0, 0, 0, 0, 0, 8, 5, 2), kv);
  _mm256_mask_storeu_pd(f, 0x7, _mm512_castpd512_pd256(_mm512_add_pd(_mm512_add_pd(first, second), third)));
}

// f[0..2] = Σ_p K_p u_{neighbour[p]} over the row's `count` blocks, four blocks per iteration
// into four accumulators (the multiply-add latency would otherwise bound the loop). A
// neighbour's displacement is one masked load (u0 u1 u2 0): the masked-off lane is never read,
// so the last node of the mesh needs no padding. One permute spreads it as
// (u0 u1 u2 u0 u1 u2 u0 u1) against the block's first eight values; K_22 u2 comes from a 4-wide
// multiply-add of the broadcast K_22 with the same load, whose third lane is kept. The row
// product is bound by instructions per block once the blocks stream from the cache, hence so
// few of them. Forced inline: the caller's row loop must not pay a call per row.
template <class Value>
[[gnu::always_inline]] inline void row(const Value* block, const Value* k22, const int* neighbour, int count,
                                       const double* u, double* f) {
  const __m512i spread = _mm512_set_epi64(1, 0, 2, 1, 0, 2, 1, 0);
  __m512d c0 = _mm512_setzero_pd(), c1 = c0, c2 = c0, c3 = c0;
  __m256d s0 = _mm256_setzero_pd(), s1 = s0, s2 = s0, s3 = s0;
  const auto add_block = [&](int p, __m512d& c, __m256d& s) {
    const __m256d x = _mm256_maskz_loadu_pd(0x7, u + neighbour[p]);
    c = _mm512_fmadd_pd(load_block(block + 8 * p), _mm512_permutexvar_pd(spread, _mm512_castpd256_pd512(x)), c);
    s = _mm256_fmadd_pd(broadcast_k22(k22 + p), x, s);
  };
  int p = 0;
  for (; p + 3 < count; p += 4) {
    add_block(p, c0, s0);
    add_block(p + 1, c1, s1);
    add_block(p + 2, c2, s2);
    add_block(p + 3, c3, s3);
  }
  for (; p < count; ++p) add_block(p, c0, s0);
  const __m256d s = _mm256_add_pd(_mm256_add_pd(s0, s1), _mm256_add_pd(s2, s3));
  store_row_sums(_mm512_add_pd(_mm512_add_pd(c0, c1), _mm512_add_pd(c2, c3)),
                 _mm_cvtsd_f64(_mm256_extractf128_pd(s, 1)), f);
}

}  // namespace softsim::fem::rows_avx512
#endif
