#pragma once
// The linear elements of the explicit engine as one precomputed, assembled stiffness:
// K_lin = Σₑ Kₑ over the linear elements (000 eq. 12 summed as in eq. 23), stored by node rows
// of 3 × 3 blocks, so that a node's linear internal force is f_a = Σ_b K_ab u_b.
//
// Why not element by element: a linear element's corner forces are Kₑ uₑ (000 eqs. 4–12), and
// producing them per element means gathering 12 displacements, storing 12 corner forces and
// summing them again at the nodes, the same data movement as a TLED element, which on this
// data path costs about as much as the TLED arithmetic itself (results/bench/summary.md). The
// superposition the paper credits linear models with (000 §1) lets the region be assembled
// once instead; a row then streams its blocks and reads each neighbour's displacement once.
// The assembled matrix depends on the mesh topology, so a cut would have to rebuild it.
//
// Every row is summed in one fixed order (its blocks by ascending neighbour), whoever
// evaluates it, so results are bit-identical for any thread count.
#include <cstring>
#include <vector>

#include "softsim/fem/aligned.hpp"
#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/element_kind.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::fem {

class LinearStiffnessRows {
 public:
  LinearStiffnessRows() = default;
  // Assembles the blocks of the elements with kinds[e] == linear (others contribute nothing).
  LinearStiffnessRows(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds, const Material& material);

  bool empty() const { return neighbour_.empty(); }
  int num_nodes() const { return static_cast<int>(row_begin_.size()) - 1; }
  int num_blocks() const { return static_cast<int>(neighbour_.size()); }
  int row_blocks(int node) const { return row_begin_[node + 1] - row_begin_[node]; }

  // f = (K_lin u) at `node`: 3 values.
  void multiply_row(int node, const double* __restrict u, double* __restrict f) const {
    // Each block is stored column by column (K_0k, K_1k, K_2k at 3k); a 4-wide load of column k
    // also takes the next value, whose product lands in lane 3 and is never used. Two sets of
    // accumulators for alternate blocks keep the FMA chains short.
    typedef double Vec4 __attribute__((vector_size(32)));
    const auto load = [](const double* p) {
      Vec4 v;
      std::memcpy(&v, p, sizeof v);
      return v;
    };
    Vec4 even = {0, 0, 0, 0}, odd = {0, 0, 0, 0};
    const int begin = row_begin_[node], end = row_begin_[node + 1];
    const double* k = block_.data() + 9 * static_cast<std::size_t>(begin);
    int p = begin;
    for (; p + 1 < end; p += 2, k += 18) {
      const double* x = u + neighbour_[p];
      const double* y = u + neighbour_[p + 1];
      even += load(k) * x[0] + load(k + 3) * x[1] + load(k + 6) * x[2];
      odd += load(k + 9) * y[0] + load(k + 12) * y[1] + load(k + 15) * y[2];
    }
    if (p < end) {
      const double* x = u + neighbour_[p];
      even += load(k) * x[0] + load(k + 3) * x[1] + load(k + 6) * x[2];
    }
    const Vec4 sum = even + odd;
    f[0] = sum[0];
    f[1] = sum[1];
    f[2] = sum[2];
  }

 private:
  std::vector<int> row_begin_;   // per node: first block of its row (n + 1 values)
  std::vector<int> neighbour_;   // per block: 3 × the column node
  AlignedVector<double> block_;  // 9 per block, column-major, plus one block of padding
};

}  // namespace softsim::fem
