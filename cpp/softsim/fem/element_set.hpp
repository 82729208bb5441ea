#pragma once
// The explicit engine's element data and kernels (000 §2.2.2–2.2.3), built for speed:
//   * elements are regrouped by kind (linear, tled, corotational, anp), each group padded to a
//     multiple of kBlock with inert elements, and stored as structure-of-arrays (node offsets,
//     the nine shape gradients of corners 1–3, the reference volume);
//   * the element phase writes each element's 12 corner forces into a per-element buffer
//     (component-major, so the vectorised kernels store contiguously);
//   * the node phase sums, for each node, its incident corner forces over a precomputed
//     node → (element, corner) list in a fixed order (000 eq. 23);
//   * elements are sorted by their highest node index and cut into tiles, so a step can sweep
//     "tile of elements, then the nodes it completed" while the buffer is still in cache.
// Linear elements are by default not computed element by element: their forces come from the
// precomputed assembled stiffness rows (linear_rows.hpp), evaluated for the nodes a tile makes
// ready and added in the node phase; LinearForces::per_element keeps the element kernel (for
// comparison, and as the route a changing topology would need).
// ANP elements (nodal_pressure.hpp) need their corners' nodal pressures, which depend on the
// neighbouring elements: a pre-pass computes det F of the ANP elements (compute_volume_ratios)
// and then the nodal pressures (update_nodal_pressures) before the element phase. Smoothed
// elements (edge_smoothing.hpp) share that pre-pass: the first pass also stores their F, the
// second also evaluates the edge stresses of the edges its nodes own.
// Every element and every node is computed the same way whatever the split into ranges, so
// results are bit-identical for any thread count: no atomics, no racy scatter, and range
// boundaries fall on block boundaries so no element ever goes through a loop remainder.
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "softsim/fem/aligned.hpp"
#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/edge_smoothing.hpp"
#include "softsim/fem/element_kernels.hpp"
#include "softsim/fem/element_kind.hpp"
#include "softsim/fem/law_data.hpp"
#include "softsim/fem/linear_rows.hpp"
#include "softsim/fem/nodal_volumes.hpp"
#include "softsim/fem/tet_geometry.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::fem {

inline constexpr int kBlock = 8;

// How the linear elements' forces are produced (see the top of this file).
enum class LinearForces { assembled, per_element };

struct KernelStats {
  double min_j = 1e300;  // smallest volume ratio J = det F seen (tled, corotational, anp)
};

class ElementSet {
 public:
  struct Group {
    ElementKind kind;
    int begin = 0;  // internal (padded) indices
    int end = 0;
    int count = 0;  // real elements (the rest is padding)
  };

  // `tile_nodes`: nodes per tile of the fused element/node sweep (see compute_tile).
  ElementSet(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds, const Material& material,
             int tile_nodes = 128, LinearForces linear_forces = LinearForces::assembled);

  int num_nodes() const { return num_nodes_; }
  int padded_size() const { return stride_; }
  const std::vector<ElementKind>& kinds() const { return kinds_; }
  const std::vector<Group>& groups() const { return groups_; }
  int count(ElementKind kind) const;
  const Material& material() const { return material_; }
  // Whether an element of `kind` may invert without that being a failure: TLED and ANP elements
  // of an inversion-robust law (material/inversion_robust.hpp). Their J is left out of
  // KernelStats::min_j and of the smallest J of energies(), and they get forces and energy at J ≤ 0.
  bool inversion_allowed(ElementKind kind) const {
    return inversion_robust_ && (kind == ElementKind::tled || kind == ElementKind::anp);
  }

  // Element phase over the whole set, in one thread: the ANP pre-pass, the assembled linear
  // rows and the corner forces of every element into the buffer, after which gather() gives
  // every node's force. J of tled, corotational and anp elements is tracked in `stats`. (The
  // explicit engine's threads sweep the tiles instead, see compute_tile.) `clock`: the step
  // whose forces these are, for a law with internal variables (law_data.hpp).
  void compute(const double* u, KernelStats& stats, const StepClock& clock = {});

  // ---- internal variables of the law (none for most laws: nothing stored, nothing done) ----
  bool has_law_state() const { return state_size_ > 0; }
  // Back to the initial (zero) state, as at the start of a run (ExplicitSolver::reset).
  void reset_law_state();
  // Internal variable c of internal slot i after step `step` (the buffer step + 1 reads).
  double law_state(int step, int i, int c) const {
    return law_state_[(step + 1) & 1][static_cast<std::size_t>(c) * stride_ + i];
  }
  int law_state_size() const { return state_size_; }
  int slot_of(int element) const { return slot_of_[element]; }

  // ---- the ANP pre-pass (nothing to do without ANP elements) ----
  bool has_nodal_pressure() const { return count(ElementKind::anp) > 0 || count(ElementKind::smoothed) > 0; }
  // det F of the ANP elements of a tile.
  void compute_volume_ratios(const double* u, int tile, KernelStats& stats);
  // p_a = κ (J_a − 1) for the nodes [begin, end), from the tiles' volume ratios, and the
  // stresses of the smoothing edges these nodes own.
  void update_nodal_pressures(int begin, int end);
  // Σ_a V_a U(J_a): the ANP elements' volumetric energy (energies() holds their isochoric part),
  // from the volume ratio of every slot as energies() writes it.
  double nodal_volumetric_energy(const double* volume_ratio) const;

  // Whether the linear elements' forces come from assembled rows (and how many blocks they have).
  bool assembled_linear() const { return !linear_rows_.empty(); }
  const LinearStiffnessRows& linear_rows() const { return linear_rows_; }
  // The values the assembled linear rows stream (linear_rows.hpp); no effect without them.
  void set_linear_precision(LinearPrecision p) { linear_rows_.set_precision(p); }

  // Node phase: the internal force on `node` (000 eq. 23), summed in a fixed order: its
  // incident corner forces, then its linear row force.
  void gather(int node, double f[3]) const {
    double fx = 0, fy = 0, fz = 0;
    const double* __restrict bx = buffer_.data();
    const double* __restrict by = bx + stride_;
    const double* __restrict bz = by + stride_;
    for (int p = incidence_begin_[node], e = incidence_end_[node]; p < e; ++p) {
      const std::size_t o = static_cast<unsigned>(incidence_[p]);
      fx += bx[o];
      fy += by[o];
      fz += bz[o];
    }
    if (assembled_linear()) {
      const double* l = linear_force_.data() + 3 * static_cast<std::size_t>(node);
      fx += l[0];
      fy += l[1];
      fz += l[2];
    }
    f[0] = fx;
    f[1] = fy;
    f[2] = fz;
  }

  // Splits [0, padded_size) into `parts` block-aligned ranges of about equal estimated cost.
  std::vector<int> balanced_ranges(int parts) const;

  // ---- tiles: the fused sweep that keeps the force buffer in cache ----
  // Tile t holds, in every group, a block-aligned run of the elements whose highest node lies
  // in [t·tile_nodes, (t+1)·tile_nodes) (rounded to whole blocks). A node is ready — all its
  // incident corner forces written — once its ready tile is computed, so a sweep "compute tile t,
  // then update the nodes ready at t" consumes the buffer while it is still in cache.
  int num_tiles() const { return num_tiles_; }
  void compute_tile(const double* u, int tile, KernelStats& stats, double* seconds = nullptr,
                    const StepClock& clock = {});
  const int* ready_nodes_begin(int tile) const { return ready_nodes_.data() + ready_begin_[tile]; }
  const int* ready_nodes_end(int tile) const { return ready_nodes_.data() + ready_begin_[tile + 1]; }
  int first_tile(int node) const { return first_tile_[node]; }
  // Estimated cost of a tile's elements, linear rows and ready nodes (units of one TLED element).
  // The costs below and relative_cost are approximate: ratios of bench_dhd timings measured once
  // on the development machine (not at start-up), used only to split the work among threads. A
  // poor estimate makes the split uneven, never the results different: forces are gathered per
  // node in a fixed order and energies summed per slot, whatever the split.
  double tile_cost(int tile) const;
  // One node's update (gather and central-difference step), approximate (bench_dhd's BM_Steps
  // node phase per node over BM_Kernel's TLED time per element).
  static constexpr double kNodeCost = 2.5;
  // One 3 × 3 block of a linear row, approximate: bench_dhd's BM_LinearRows per block over
  // BM_Kernel's TLED time per element.
  static constexpr double kLinearBlockCost = 0.17;

  // Reference shape of internal slot i (gradients and volume as stored).
  TetShape shape(int internal) const;
  // Corner displacements of internal slot i.
  Corners corners(int internal, const double* u) const;
  // Strain energy ⁰V W of each internal slot in [begin, end) into energy[internal] (padding: 0),
  // its J = det F into volume_ratio[internal] (padding: 1), and the smallest J in the range with
  // its original element index.
  void energies(const double* u, int begin, int end, double* energy, double* volume_ratio, double& min_j,
                int& min_j_element) const;

  // Approximate relative cost of one element of each kind (for balancing threads), tled = 1.
  static double relative_cost(ElementKind kind);

  // ---- cutting by element removal ----
  // Removes elements (original indices; ones already removed are skipped) by a local update,
  // with nothing rebuilt: each one's slot keeps its place but loses its shape gradients and
  // volume, so its kernel yields F = I, zero corner forces and zero energy (the tiles, thread
  // ranges and node gathers stay as they are, adding zeros); a linear element's blocks leave
  // the assembled rows; an ANP element leaves its corners' nodal volumes and weights. The
  // element set then computes the forces of the mesh without those elements (to round-off).
  // `mesh` is the mesh the set was built on. Returns the elements actually removed.
  std::vector<int> remove_elements(const mesh::TetMesh& mesh, const std::vector<int>& elements);
  bool removed(int element) const { return removed_[element] != 0; }
  int num_removed() const { return num_removed_; }

  // ---- cutting by separation along faces (cutting/separation.hpp) ----
  // A node split: `copy` (numbered after every node so far, in order) takes over `node` as a
  // corner of `elements`. A local update: the moved slots' corners point at the copy, their
  // incident corner forces leave the node's gather list for the copy's (appended), and ANP
  // elements move their nodal-volume share (a moved element keeps a zero-weight entry at the
  // node, as a removed one does). Shape gradients, volumes and tiles are untouched: a copy has
  // its node's reference position. A copy is ready in no tile; its owner updates it once the
  // whole element phase is done. Assembled linear elements cannot move (their rows' pattern
  // would change): a set built for separation computes them per element (LinearForces).
  // `mesh`: the set's mesh after the split (the copies appended, the elements re-pointed).
  struct NodeCopy {
    int node = 0;
    int copy = 0;
    std::vector<int> elements;
  };
  void split_nodes(const mesh::TetMesh& mesh, const std::vector<NodeCopy>& copies);

 private:
  void compute_group(const Group& g, const double* u, int begin, int end, KernelStats& stats,
                     const StepClock& clock);
  kernels::LawData law_data(const StepClock& clock);
  bool computed_per_element(const Group& g) const { return g.kind != ElementKind::linear || !assembled_linear(); }
  void compute_linear_rows(const double* u, const int* node_begin, const int* node_end);
  void build_tiles(const std::vector<int>& key, int tile_nodes);
  void build_nodal_pressure(const mesh::TetMesh& mesh);
  void compute_smoothed(const double* u, int begin, int end);
  void rebuild_smoothing(const mesh::TetMesh& mesh);
  Eigen::Matrix3d slot_gradient(int i, const double* u) const;
  void reweigh_nodal_volume(int node);
  kernels::SoaView view();

  int num_nodes_ = 0;
  int stride_ = 0;  // padded element count: component c of slot i lives at buffer[c * stride + i]
  Material material_;
  bool inversion_robust_ = false;  // material::inversion_robust(material_.law)
  std::vector<ElementKind> kinds_;  // per original element
  std::vector<int> original_;       // internal slot -> original element (−1: padding)
  std::vector<int> slot_of_;        // original element -> internal slot
  std::vector<char> removed_;       // per original element: removed by a cut
  int num_removed_ = 0;
  std::vector<Group> groups_;
  std::array<AlignedVector<int>, 4> node_offset_;  // 3 × node index of each corner
  std::array<AlignedVector<double>, 9> grad_;      // ∇N of corners 1..3 (x, y, z each)
  AlignedVector<double> volume_;
  AlignedVector<double> buffer_;   // 12 × stride corner forces
  AlignedVector<double> scratch_;  // per slot: what a kernel's fix-up pass decides on (J, polar convergence)
  // A law with a fibre: its unit direction per slot (x, y, z); a law with internal variables:
  // state_size_ doubles per slot in each of two buffers (law_data.hpp). Empty otherwise.
  std::array<AlignedVector<double>, 3> fibre_;
  std::array<AlignedVector<double>, 2> law_state_;
  int state_size_ = 0;
  // ANP: det F per slot, the node → (element, weight) lists with elements given by their slot,
  // and p_a at index 3a.
  AlignedVector<double> volume_ratio_;
  NodalVolumes anp_;
  AlignedVector<double> nodal_pressure_;
  // Smoothed elements: their edges, F per original element and P_iso per edge of the step.
  std::optional<EdgeSmoothing> smoothing_;
  std::vector<Eigen::Matrix3d> smoothed_gradient_;
  std::vector<Eigen::Matrix3d> edge_stress_;
  // Assembled linear rows and, per node, the row force of the current element phase.
  LinearStiffnessRows linear_rows_;
  AlignedVector<double> linear_force_;
  // Per node, its incident corners' buffer offsets (x component) are incidence_[begin, end): a
  // node's range only shrinks when a split moves corners away; a copy's range is appended.
  std::vector<int> incidence_begin_, incidence_end_;
  std::vector<int> incidence_;
  int num_tiles_ = 1;
  std::vector<std::pair<int, int>> tile_blocks_;  // [tile * groups + group] -> slot range
  std::vector<int> first_tile_;                   // per node
  std::vector<int> ready_begin_, ready_nodes_;    // per tile: nodes ready there (ascending)
};

}  // namespace softsim::fem
