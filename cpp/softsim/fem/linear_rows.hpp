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
// The assembled matrix depends on the mesh topology; a cut that removes a linear element
// subtracts its blocks (remove_element), a local update.
//
// Storage: eight values of each block fill one 64-byte line and K_22 lives in a separate array;
// the order of the eight is the one the build's vector kernel consumes without shuffling
// (kBlockSlot below). With AVX-512 they are row by row (K_00 K_01 K_02 K_10 K_11 K_12 K_20 K_21),
// so that a single 8-wide multiply-add takes a whole block against the neighbour's displacement
// spread as (u0 u1 u2 u0 u1 u2 u0 u1); otherwise they are (K_00 K_01 K_10 K_11 | K_20 K_21 K_02
// K_12), two 4-wide halves taken against (u0 u1 u0 u1) and (u0 u1 u2 u2), which are a broadcast
// load and a blend away from the displacement in memory. A row's three sums are formed once at
// its end.
//
// Every row is summed in one fixed order (its blocks by ascending neighbour), whoever
// evaluates it, so results are bit-identical for any thread count.
//
// Precision (LinearPrecision): the product is bound by the bytes of its blocks, not by its
// arithmetic, whenever they stream from a shared cache or memory (cpp/apps/dhd_sim.md, speed).
// On request the rows are streamed as single-precision values (a copy of the blocks rounded to
// float: 40 instead of 76 bytes per block with its index) and multiplied in double precision
// against the double displacements, accumulating in double; the double blocks are kept, so a
// removed element leaves the exact sums and only the touched blocks are rounded again. The
// default is double, bit for bit the product of the double blocks.
#include <vector>

#include "softsim/fem/aligned.hpp"
#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/element_kind.hpp"
#include "softsim/fem/linear_rows_avx512.hpp"  // SOFTSIM_ROWS_AVX512: which storage order (kBlockSlot)
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::fem {

// The values the linear rows stream: the assembled double blocks, or those rounded to float
// (the product still sums in double). `solver.linear_precision` in dhd_sim's config.
enum class LinearPrecision { double_precision, single_precision };
const char* linear_precision_name(LinearPrecision p);

class LinearStiffnessRows {
 public:
  // Which code evaluates the rows: the vector kernel the build targets (AVX-512, else AVX2 with
  // FMA: linear_rows_avx512.hpp, linear_rows_avx2.hpp), otherwise
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
    return row == 2 && col == 2 ? k22_[block] : block_[8 * static_cast<std::size_t>(block) + kBlockSlot[row][col]];
  }
  // Subtracts linear element e's blocks Kₑ (a cut removed it): the rows keep their pattern, the
  // element's share leaves them (to round-off: (K + Kₑ) − Kₑ). A local update of 16 blocks.
  void remove_element(const mesh::TetMesh& mesh, int e, const Material& material) {
    add_element(mesh, e, material, -1.0);
  }

  // Which values multiply_rows streams (default double). Single precision rounds a copy of the
  // blocks to float; double frees that copy.
  void set_precision(LinearPrecision precision);
  LinearPrecision precision() const { return precision_; }

  // Whether Kernel::best is a vector kernel (AVX-512 or AVX2) in this build.
  static bool vectorised();

  // f[3a..3a+2] = (K_lin u) at every node a of [nodes_begin, nodes_end) that has a row; nodes
  // without one are left untouched. `u` and `f` hold 3 values per node of the mesh.
  void multiply_rows(const int* nodes_begin, const int* nodes_end, const double* u, double* f,
                     Kernel kernel = Kernel::best) const;

 private:
  // Where K_rc of a block sits among its eight values in block_ (K_22, marked −1, is in k22_):
  // the order of the kernel multiply_rows picks for this build.
#ifdef SOFTSIM_ROWS_AVX512
  static constexpr int kBlockSlot[3][3] = {{0, 1, 2}, {3, 4, 5}, {6, 7, -1}};
#else
  static constexpr int kBlockSlot[3][3] = {{0, 1, 6}, {2, 3, 7}, {4, 5, -1}};
#endif

  void add_element(const mesh::TetMesh& mesh, int e, const Material& material, double sign);
  // Rounds block p's double values into the single-precision copy.
  void round_block(std::size_t p);

  template <class Value, class Row>
  void for_each_row(const Value* block, const Value* k22, const int* nodes_begin, const int* nodes_end,
                    const double* u, double* f, Row row) const;
  template <class Value>
  void multiply_rows_of(const Value* block, const Value* k22, const int* nodes_begin, const int* nodes_end,
                        const double* u, double* f, Kernel kernel) const;

  std::vector<int> row_begin_;   // per node: first block of its row (n + 1 values)
  std::vector<int> neighbour_;   // per block: 3 × the column node
  AlignedVector<double> block_;  // 8 per block: every K_rc but K_22, in the order of kBlockSlot
  std::vector<double> k22_;      // per block: K_22
  LinearPrecision precision_ = LinearPrecision::double_precision;
  AlignedVector<float> block_single_;  // with single precision: block_ rounded to float
  AlignedVector<float> k22_single_;    // with single precision: k22_ rounded to float
};

}  // namespace softsim::fem
