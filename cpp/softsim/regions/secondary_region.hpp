#pragma once
// The secondary region of the linked asynchronous regions (001 §5) as a linear, quasi-static
// model whose factorisation is computed once: the cheap far field of 000 (small-strain
// elements) solved with precomputation, where precomputation pays. Two couplings to the
// primary region:
//
//   Exchange (001 eq. 7): every k-th frame the secondary solves its own rows of the linear
//     system with the primary's interior displacements on the right-hand side,
//       K_SS u_S = f_S − K_SP u_P,
//     S = every free dof outside the primary interior (interface included), K the small-strain
//     stiffness of the whole mesh. The primary region sees the interface values it publishes.
//
//   Condensation: the secondary elements' stiffness K^s is condensed onto the interface once
//     (the Schur complement with the secondary's own nodes eliminated, as in local-model and
//     static-condensation methods),
//       S_II = K^s_II − K^s_IS (K^s_SS)^-1 K^s_SI,   h = K^s_IS (K^s_SS)^-1 f_S,
//     and the primary region carries the interface force −S_II u_I − h at every explicit
//     substep: the exact quasi-static response of a linear secondary region, no lag. The
//     secondary's own displacement is recovered only when a picture needs it.
//
//   Condensation with the far field's inertia (Guyan 1965): the secondary moves in the static
//     shape its interface imposes, u_S = Ψ u_I with Ψ = −(K^s_SS)^-1 K^s_SI, so its kinetic energy
//     is ½ u̇_Iᵀ (Ψᵀ M_SS Ψ) u̇_I. That mass, lumped by row sums onto the interface nodes, is added
//     to the primary region's interface nodes: the far field's inertia with no lag and no cost
//     per substep (a heavier interface only lengthens the critical step). Exact in statics;
//     in dynamics it misses only the far field's motion relative to that static shape.
//
//   Condensation with a modal far field (Craig & Bampton 1968): u_S = Ψ u_I + Φ η with Φ a few
//     fixed-interface modes (far_field_modes.hpp). Written in z = η + L u_I, L = Φᵀ M_SS Ψ (the
//     modal coordinates of the far field's whole displacement), the kinetic energy separates,
//       T = ½ u̇_Iᵀ (Ψᵀ M_SS Ψ − LᵀL) u̇_I + ½ żᵀż,
//     and the potential is ½ u_Iᵀ S_II u_I + ½ (z − L u_I)ᵀ Ω² (z − L u_I), so
//       interface force  −S_II u_I + LᵀΩ² (z − L u_I),   residual mass Ψᵀ M_SS Ψ − LᵀL (lumped),
//       each mode        z̈ + α ż + Ω² z = Ω² L u_I,
//     driven by the interface's displacement alone: no mass coupling, so each mode takes the same
//     explicit central-difference step as the primary region (000 eq. 33) at the cost of a
//     product with L per substep. No modes: Guyan. Every mode: the whole linear far field.
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "softsim/fem/constitutive.hpp"
#include "softsim/mesh/tet_mesh.hpp"
#include "softsim/regions/far_field_modes.hpp"
#include "softsim/regions/primary_region.hpp"
#include "softsim/regions/sparse_cholesky.hpp"

namespace softsim::regions {

// What both couplings share: the mesh, the small-strain stiffness of every element and the
// constrained dofs (held at zero), built once per scene.
struct LinearModel {
  // `removed` (per element, or empty): elements a cut took out, left out of K.
  LinearModel(const mesh::TetMesh& mesh, const fem::Material& material, std::vector<char> constrained,
              Eigen::VectorXd gravity_force, std::vector<double> masses = {}, double damping_alpha = 0,
              std::vector<char> removed = {});
  const mesh::TetMesh* mesh;
  fem::Material material;
  std::vector<double> masses;       // lumped, per node (an implicit-dynamic secondary's inertia)
  double damping_alpha = 0;         // D = α M
  std::vector<char> constrained;    // per dof
  Eigen::VectorXd gravity_force;    // M g per dof at full gravity (zero without gravity)
  std::vector<char> removed;        // per element: taken out by a cut (empty: none)
  Eigen::SparseMatrix<double> K;    // small-strain stiffness of the whole mesh
  bool live(int element) const { return removed.empty() || !removed[element]; }
};

class ExchangeSecondary {
 public:
  // `step` > 0: the secondary is implicit-dynamic with that step (Newmark's average acceleration,
  // unconditionally stable; 001 §4's implicit solver): its own lumped mass and damping enter,
  // K_eff = K_SS + (4/H² + 2α/H) M_SS, factorised once. `step` = 0: quasi-static.
  // NumericalError if the secondary block is singular (a secondary piece held by nothing).
  ExchangeSecondary(const LinearModel& model, const PrimaryRegion& region, double step = 0);
  // Reads the primary interior's dofs of `u` (3 per node, global), writes the secondary's
  // (interface included); `gravity_factor` scales the gravity load (its ramp). Dynamic: one step
  // of H from the last solution.
  void solve(double* u, double gravity_factor);
  // Dynamic: the secondary at `u` (global), at rest.
  void start_at(const double* u);
  bool dynamic() const { return step_ > 0; }
  int dofs() const { return static_cast<int>(secondary_.size()); }

 private:
  const LinearModel* model_;
  std::vector<int> secondary_, primary_;  // global dofs
  Eigen::SparseMatrix<double> K_sp_;
  SparseCholesky solver_;
  Eigen::VectorXd u_p_, rhs_;
  double step_ = 0;
  Eigen::VectorXd mass_, u_s_, v_s_, a_s_;  // dynamic: lumped mass per dof and the state
};

class CondensedSecondary {
 public:
  CondensedSecondary(const LinearModel& model, const PrimaryRegion& region);
  // The secondary's force on the interface nodes at interface displacement `u_interface`
  // (3 per interface node, in region.interface order): −S_II u_I − gravity_factor h, written to
  // `force` (same layout; constrained components zero). No allocation.
  void interface_force(const double* u_interface, double gravity_factor, double* force);
  // The secondary nodes' displacement for the interface displacement in `u` (global, 3 per
  // node): u_S = (K^s_SS)^-1 (f_S − K^s_SI u_I), written into `u`.
  void recover(double* u, double gravity_factor);
  // Deferred recovery (nobody may read the far field before the next one is due): what
  // recover() would read now (u_I, the modes' state, the gravity factor) is kept, and the solve
  // is done only if recover_kept() is called before the next keep(). recover_kept() writes
  // exactly what recover() would have written at keep() time. No allocation.
  void keep_for_recovery(const double* u, double gravity_factor);
  bool recovery_kept() const { return kept_; }
  void recover_kept(double* u);
  void drop_kept() { kept_ = false; }
  int interface_dofs() const { return static_cast<int>(interface_.size()); }
  int secondary_dofs() const { return static_cast<int>(secondary_.size()); }
  // Guyan: the far field's mass carried by each interface node (kg, in region.interface order):
  // the row sums of Ψᵀ M_SS Ψ along each direction, averaged over the node's free directions,
  // from two solves per direction. Needs the model's lumped masses.
  // With modes (use_modes), less the part the modes carry (LᵀL, row sums likewise).
  std::vector<double> interface_masses();
  // Keeps the `count` lowest fixed-interface modes of the far field, stepped with the primary
  // region's explicit step `dt` and damping α M (Craig–Bampton, above). Needs the lumped masses.
  // Call before interface_masses().
  void use_modes(int count, double dt, double damping_alpha);
  int modes() const { return static_cast<int>(omega2_.size()); }
  const Eigen::VectorXd& mode_omega2() const { return omega2_; }
  // Modes: the state from the far field's displacement in `u` (global), at rest: z = Φᵀ M_SS u_S.
  void start_modes(const double* u);
  // The same with the far field's displacement one step earlier in `u_before` (global, or null:
  // at rest): the modes resume with their velocity, z_before = Φᵀ M_SS u_S(before).
  void start_modes(const double* u, const double* u_before);
  // The far field one explicit step ago into `u_before` (global): recovered from the interface's
  // displacement in `u_before` and the modes' state of that step. No allocation after the first.
  void recover_previous(double* u_before, double gravity_factor);
  // Modes: one explicit step of every mode, forced by the interface displacement the last
  // interface_force() saw (000 eq. 33 with unit modal mass). No allocation.
  void advance_modes();
  // Stores S_II in single precision and evaluates the interface product in it: half the memory
  // traffic of the dense product that dominates a large interface's substep. S_II's entries keep
  // a relative error of 2^-24 (the product's error stays far below the far field's own).
  void use_single_precision();
  bool single_precision() const { return S32_.size() > 0; }

 private:
  const LinearModel* model_;
  std::vector<int> interface_, secondary_;  // global free dofs
  int interface_nodes_ = 0;
  std::vector<int> interface_slot_;         // per interface dof: its index in the 3-per-node interface layout
  Eigen::MatrixXd S_;                       // condensed interface stiffness (empty in single precision)
  Eigen::MatrixXf S32_;                     // the same in single precision, when chosen
  Eigen::VectorXf u32_, f32_;
  Eigen::VectorXd h_;                       // condensed gravity load at full gravity
  Eigen::SparseMatrix<double> K_si_;
  Eigen::VectorXd g_s_;                     // gravity on the secondary dofs at full gravity
  SparseCholesky solver_;
  Eigen::VectorXd u_i_, f_i_, rhs_;
  // Modes (Craig–Bampton): Φ (secondary dofs × m), Ω², L = Φᵀ M Ψ (m × interface dofs), the
  // interface coupling G = LᵀΩ², the state z now and one step ago, and L u_I of the last
  // interface_force(); the central-difference coefficients of a unit modal mass.
  Eigen::MatrixXd phi_, L_, G_;
  Eigen::VectorXd omega2_, z_, z_before_, Lu_, eta_, z_next_;
  // Deferred recovery: the interface displacement, modal state and gravity factor kept.
  Eigen::VectorXd kept_u_i_, kept_z_, kept_Lu_;
  double kept_gravity_ = 0;
  bool kept_ = false;
  double cd_A_ = 0, cd_B_ = 1, cd_C_ = 0;
};

}  // namespace softsim::regions
