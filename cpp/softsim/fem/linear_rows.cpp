#include "softsim/fem/linear_rows.hpp"

#include <algorithm>
#include <cstring>

#include "softsim/fem/element_response.hpp"
#include "softsim/fem/tet_geometry.hpp"

#if defined(__AVX512F__) && defined(__AVX512VL__)
#include <immintrin.h>
#define SOFTSIM_ROWS_AVX512 1
#endif

namespace softsim::fem {

LinearStiffnessRows::LinearStiffnessRows(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds,
                                         const Material& material) {
  const int n = mesh.num_nodes();
  // Row pattern: every node paired with itself and each node it shares a linear element with.
  std::vector<std::vector<int>> columns(n);
  for (int e = 0; e < mesh.num_tets(); ++e) {
    if (kinds[e] != ElementKind::linear) continue;
    for (int a : mesh.tets[e])
      for (int b : mesh.tets[e]) columns[a].push_back(b);
  }
  row_begin_.assign(n + 1, 0);
  for (int a = 0; a < n; ++a) {
    auto& c = columns[a];
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    row_begin_[a + 1] = row_begin_[a] + static_cast<int>(c.size());
  }
  if (row_begin_[n] == 0) return;  // no linear element: nothing to store
  neighbour_.resize(row_begin_[n]);
  for (int a = 0; a < n; ++a)
    for (std::size_t j = 0; j < columns[a].size(); ++j) neighbour_[row_begin_[a] + j] = 3 * columns[a][j];
  block_.assign(8 * static_cast<std::size_t>(row_begin_[n]), 0.0);
  k22_.assign(row_begin_[n], 0.0);

  // Element blocks Kₑ (the linear element's 12 × 12 stiffness, the same function the static
  // solver assembles) added into their rows.
  const Corners zero{};
  for (int e = 0; e < mesh.num_tets(); ++e) {
    if (kinds[e] != ElementKind::linear) continue;
    const ElementMatrix K = element_tangent(material, ElementKind::linear, tet_shape(mesh, e), zero);
    const auto& t = mesh.tets[e];
    for (int a = 0; a < 4; ++a) {
      const int* first = neighbour_.data() + row_begin_[t[a]];
      const int* last = neighbour_.data() + row_begin_[t[a] + 1];
      for (int b = 0; b < 4; ++b) {
        const std::size_t p = std::lower_bound(first, last, 3 * t[b]) - neighbour_.data();
        double* block = block_.data() + 8 * p;
        for (int row = 0; row < 3; ++row)
          for (int col = 0; col < 3; ++col) {
            const double k = K(3 * a + row, 3 * b + col);
            if (row == 2 && col == 2)
              k22_[p] += k;
            else
              block[3 * row + col] += k;
          }
      }
    }
  }
}

bool LinearStiffnessRows::vectorised() {
#ifdef SOFTSIM_ROWS_AVX512
  return true;
#else
  return false;
#endif
}

namespace {

// One row in portable code (GCC vector extensions, lowered to whatever the target has): the same
// layout as the AVX-512 kernel, but two accumulators instead of four, so the two kernels' sums
// differ in the last bits (each is the same for any thread count).
typedef double Vec8 __attribute__((vector_size(64)));

inline Vec8 load8(const double* p) {
  Vec8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void portable_row(const double* block, const double* k22, const int* neighbour, int count, const double* u,
                         double* f) {
  Vec8 even = {0, 0, 0, 0, 0, 0, 0, 0}, odd = even;
  double s0 = 0, s1 = 0;
  int p = 0;
  for (; p + 1 < count; p += 2) {
    const double* x = u + neighbour[p];
    const double* y = u + neighbour[p + 1];
    even += load8(block + 8 * p) * Vec8{x[0], x[1], x[2], x[0], x[1], x[2], x[0], x[1]};
    odd += load8(block + 8 * p + 8) * Vec8{y[0], y[1], y[2], y[0], y[1], y[2], y[0], y[1]};
    s0 += k22[p] * x[2];
    s1 += k22[p + 1] * y[2];
  }
  if (p < count) {
    const double* x = u + neighbour[p];
    even += load8(block + 8 * p) * Vec8{x[0], x[1], x[2], x[0], x[1], x[2], x[0], x[1]};
    s0 += k22[p] * x[2];
  }
  const Vec8 t = even + odd;
  f[0] = t[0] + t[1] + t[2];
  f[1] = t[3] + t[4] + t[5];
  f[2] = t[6] + t[7] + (s0 + s1);
}

#ifdef SOFTSIM_ROWS_AVX512
// (u0 u1 u2 u0 u1 u2 u0 u1) of a neighbour, matching a block's first eight values row by row,
// from u0 u1 and the separately loaded u2 (which K_22 needs too): no load reaches past u2, so
// the last node of the mesh needs no padding.
inline __m512d spread(__m512i pattern, const double* x, __m128d x2) {
  return _mm512_permutex2var_pd(_mm512_castpd128_pd512(_mm_loadu_pd(x)), pattern, _mm512_castpd128_pd512(x2));
}

// One row, four blocks per iteration into four accumulators (the multiply-add latency would
// otherwise bound the loop); K_22 u_2 goes to two scalar sums.
inline void avx512_row(const double* block, const double* k22, const int* neighbour, int count, const double* u,
                       double* f) {
  const __m512i pattern = _mm512_set_epi64(1, 0, 8, 1, 0, 8, 1, 0);  // lane 8: the first of x2
  __m512d c0 = _mm512_setzero_pd(), c1 = c0, c2 = c0, c3 = c0;
  double s0 = 0, s1 = 0;
  int p = 0;
  for (; p + 3 < count; p += 4) {
    const double* x = u + neighbour[p];
    const double* y = u + neighbour[p + 1];
    const double* z = u + neighbour[p + 2];
    const double* w = u + neighbour[p + 3];
    const __m128d x2 = _mm_load_sd(x + 2), y2 = _mm_load_sd(y + 2), z2 = _mm_load_sd(z + 2), w2 = _mm_load_sd(w + 2);
    c0 = _mm512_fmadd_pd(_mm512_load_pd(block + 8 * p), spread(pattern, x, x2), c0);
    c1 = _mm512_fmadd_pd(_mm512_load_pd(block + 8 * p + 8), spread(pattern, y, y2), c1);
    c2 = _mm512_fmadd_pd(_mm512_load_pd(block + 8 * p + 16), spread(pattern, z, z2), c2);
    c3 = _mm512_fmadd_pd(_mm512_load_pd(block + 8 * p + 24), spread(pattern, w, w2), c3);
    s0 += k22[p] * _mm_cvtsd_f64(x2) + k22[p + 2] * _mm_cvtsd_f64(z2);
    s1 += k22[p + 1] * _mm_cvtsd_f64(y2) + k22[p + 3] * _mm_cvtsd_f64(w2);
  }
  for (; p < count; ++p) {
    const double* x = u + neighbour[p];
    const __m128d x2 = _mm_load_sd(x + 2);
    c0 = _mm512_fmadd_pd(_mm512_load_pd(block + 8 * p), spread(pattern, x, x2), c0);
    s0 += k22[p] * _mm_cvtsd_f64(x2);
  }
  alignas(64) double t[8];
  _mm512_store_pd(t, _mm512_add_pd(_mm512_add_pd(c0, c1), _mm512_add_pd(c2, c3)));
  f[0] = t[0] + t[1] + t[2];
  f[1] = t[3] + t[4] + t[5];
  f[2] = t[6] + t[7] + (s0 + s1);
}
#endif

}  // namespace

// The row loop is instantiated per kernel so that the row body is inlined into it: a call per
// row (a dozen blocks) would cost a sizeable share of the row itself.
template <class Row>
void LinearStiffnessRows::for_each_row(const int* nodes_begin, const int* nodes_end, const double* u, double* f,
                                       Row row) const {
  for (const int* n = nodes_begin; n != nodes_end; ++n) {
    const int begin = row_begin_[*n], count = row_begin_[*n + 1] - begin;
    if (count > 0)
      row(block_.data() + 8 * static_cast<std::size_t>(begin), k22_.data() + begin, neighbour_.data() + begin, count,
          u, f + 3 * static_cast<std::size_t>(*n));
  }
}

void LinearStiffnessRows::multiply_rows(const int* nodes_begin, const int* nodes_end, const double* u, double* f,
                                        Kernel kernel) const {
#ifdef SOFTSIM_ROWS_AVX512
  if (kernel == Kernel::best) return for_each_row(nodes_begin, nodes_end, u, f, avx512_row);
#else
  (void)kernel;
#endif
  for_each_row(nodes_begin, nodes_end, u, f, portable_row);
}

}  // namespace softsim::fem
