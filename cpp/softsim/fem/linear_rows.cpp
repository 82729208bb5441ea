#include "softsim/fem/linear_rows.hpp"

#include <algorithm>

#include "softsim/fem/element_response.hpp"
#include "softsim/fem/linear_rows_avx2.hpp"
#include "softsim/fem/tet_geometry.hpp"

namespace softsim::fem {

const char* linear_precision_name(LinearPrecision p) {
  return p == LinearPrecision::single_precision ? "single" : "double";
}

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
  for (int e = 0; e < mesh.num_tets(); ++e)
    if (kinds[e] == ElementKind::linear) add_element(mesh, e, material, 1.0);
}

void LinearStiffnessRows::add_element(const mesh::TetMesh& mesh, int e, const Material& material, double sign) {
  const Corners zero{};
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
          const double k = sign * K(3 * a + row, 3 * b + col);
          if (row == 2 && col == 2)
            k22_[p] += k;
          else
            block[kBlockSlot[row][col]] += k;
        }
      if (precision_ == LinearPrecision::single_precision) round_block(p);
    }
  }
}

void LinearStiffnessRows::round_block(std::size_t p) {
  for (int q = 0; q < 8; ++q) block_single_[8 * p + q] = static_cast<float>(block_[8 * p + q]);
  k22_single_[p] = static_cast<float>(k22_[p]);
}

void LinearStiffnessRows::set_precision(LinearPrecision precision) {
  precision_ = precision;
  if (precision == LinearPrecision::double_precision) {
    AlignedVector<float>().swap(block_single_);
    AlignedVector<float>().swap(k22_single_);
    return;
  }
  block_single_.resize(block_.size());
  k22_single_.resize(k22_.size());
  for (std::size_t p = 0; p < k22_.size(); ++p) round_block(p);
}

bool LinearStiffnessRows::vectorised() {
#if defined(SOFTSIM_ROWS_AVX512) || defined(SOFTSIM_ROWS_AVX2)
  return true;
#else
  return false;
#endif
}

namespace {

// One row in plain loops, for builds without a vector kernel and to check the vector kernels:
// f_r = Σ_p Σ_c K_rc u_c with the values found through `slot` (the storage order of kBlockSlot).
// Its sums run in another order than the vector kernels', so they differ in the last bits (each
// is the same for any thread count).
template <class Value>
[[gnu::always_inline]] inline void portable_row(const Value* block, const Value* k22, const int* neighbour,
                                                int count, const double* u, double* f, const int (&slot)[3][3]) {
  double f0 = 0, f1 = 0, f2 = 0;
  for (int p = 0; p < count; ++p) {
    const double* x = u + neighbour[p];
    const Value* k = block + 8 * p;
    f0 += double(k[slot[0][0]]) * x[0] + double(k[slot[0][1]]) * x[1] + double(k[slot[0][2]]) * x[2];
    f1 += double(k[slot[1][0]]) * x[0] + double(k[slot[1][1]]) * x[1] + double(k[slot[1][2]]) * x[2];
    f2 += double(k[slot[2][0]]) * x[0] + double(k[slot[2][1]]) * x[1] + double(k22[p]) * x[2];
  }
  f[0] = f0;
  f[1] = f1;
  f[2] = f2;
}

}  // namespace

// The row loop is instantiated per kernel so that the row body is inlined into it: a call per
// row (a dozen blocks) would cost a sizeable share of the row itself. The kernels are passed as
// lambdas, whose distinct types give one instantiation each (a function pointer would give one
// instantiation for both and a call per row), and the kernels are forced inline (GCC judges
// them too large to inline on its own).
template <class Value, class Row>
void LinearStiffnessRows::for_each_row(const Value* block, const Value* k22, const int* nodes_begin,
                                       const int* nodes_end, const double* u, double* f, Row row) const {
  for (const int* n = nodes_begin; n != nodes_end; ++n) {
    const int begin = row_begin_[*n], count = row_begin_[*n + 1] - begin;
    if (count > 0)
      row(block + 8 * static_cast<std::size_t>(begin), k22 + begin, neighbour_.data() + begin, count, u,
          f + 3 * static_cast<std::size_t>(*n));
  }
}

template <class Value>
void LinearStiffnessRows::multiply_rows_of(const Value* block, const Value* k22, const int* nodes_begin,
                                           const int* nodes_end, const double* u, double* f, Kernel kernel) const {
#if defined(SOFTSIM_ROWS_AVX512)
  if (kernel == Kernel::best)
    return for_each_row(block, k22, nodes_begin, nodes_end, u, f,
                        [](auto... row) __attribute__((always_inline)) { rows_avx512::row(row...); });
#elif defined(SOFTSIM_ROWS_AVX2)
  if (kernel == Kernel::best)
    return for_each_row(block, k22, nodes_begin, nodes_end, u, f,
                        [](auto... row) __attribute__((always_inline)) { rows_avx2::row(row...); });
#else
  (void)kernel;
#endif
  for_each_row(block, k22, nodes_begin, nodes_end, u, f,
               [](auto... row) __attribute__((always_inline)) { portable_row(row..., kBlockSlot); });
}

void LinearStiffnessRows::multiply_rows(const int* nodes_begin, const int* nodes_end, const double* u, double* f,
                                        Kernel kernel) const {
  if (precision_ == LinearPrecision::single_precision)
    multiply_rows_of(block_single_.data(), k22_single_.data(), nodes_begin, nodes_end, u, f, kernel);
  else
    multiply_rows_of(block_.data(), k22_.data(), nodes_begin, nodes_end, u, f, kernel);
}

}  // namespace softsim::fem
