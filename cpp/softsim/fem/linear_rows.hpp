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
// Storage: the first eight values of each block, row by row (K_00 K_01 K_02 K_10 K_11 K_12 K_20
// K_21), fill one 64-byte line, so that a single 8-wide multiply-add takes a whole block against
// the neighbour's displacement laid out as (u0 u1 u2 u0 u1 u2 u0 u1); K_22 lives in a separate
// array. A row's three sums are formed once at its end.
//
// Every row is summed in one fixed order (its blocks by ascending neighbour), whoever
// evaluates it, so results are bit-identical for any thread count.
#include <vector>

#include "softsim/fem/aligned.hpp"
#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/element_kind.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::fem {

class LinearStiffnessRows {
 public:
  // Which code evaluates the rows: the 8-wide one where the build targets AVX-512, otherwise
  // (and on request, to check one against the other) plain loops.
  enum class Kernel { best, portable };

  LinearStiffnessRows() = default;
  // Assembles the blocks of the elements with kinds[e] == linear (others contribute nothing).
  LinearStiffnessRows(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds, const Material& material);

  bool empty() const { return neighbour_.empty(); }
  int num_blocks() const { return static_cast<int>(neighbour_.size()); }
  int row_blocks(int node) const { return row_begin_[node + 1] - row_begin_[node]; }
  // Read access to the stored blocks (for measurements of other storage schemes): the blocks of
  // a node's row are first_block(node) .. first_block(node) + row_blocks(node) − 1.
  int first_block(int node) const { return row_begin_[node]; }
  int column_node(int block) const { return neighbour_[block] / 3; }
  double value(int block, int row, int col) const {
    return row == 2 && col == 2 ? k22_[block] : block_[8 * static_cast<std::size_t>(block) + 3 * row + col];
  }
  // Whether Kernel::best is the 8-wide kernel in this build.
  static bool vectorised();

  // f[3a..3a+2] = (K_lin u) at every node a of [nodes_begin, nodes_end) that has a row; nodes
  // without one are left untouched. `u` and `f` hold 3 values per node of the mesh.
  void multiply_rows(const int* nodes_begin, const int* nodes_end, const double* u, double* f,
                     Kernel kernel = Kernel::best) const;

 private:
  template <class Row>
  void for_each_row(const int* nodes_begin, const int* nodes_end, const double* u, double* f, Row row) const;

  std::vector<int> row_begin_;   // per node: first block of its row (n + 1 values)
  std::vector<int> neighbour_;   // per block: 3 × the column node
  AlignedVector<double> block_;  // 8 per block: K_00 .. K_21 row by row
  std::vector<double> k22_;      // per block: K_22
};

}  // namespace softsim::fem
