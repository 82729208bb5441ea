#include "softsim/regions/secondary_region.hpp"

#include <algorithm>
#include <utility>

#include "softsim/dynamics/central_difference.hpp"
#include "softsim/fem/assembly.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/regions/dof_blocks.hpp"

namespace softsim::regions {

namespace {

Eigen::SparseMatrix<double> small_strain_stiffness(const mesh::TetMesh& mesh, const fem::Material& material) {
  const fem::Assembler a(mesh, std::vector<fem::ElementKind>(mesh.num_tets(), fem::ElementKind::linear), material);
  Eigen::SparseMatrix<double> K = a.pattern();
  const std::vector<double> zero(a.num_dofs(), 0.0);
  a.tangent(zero.data(), K);
  return K;
}

Eigen::VectorXd gather(const Eigen::VectorXd& v, const std::vector<int>& dofs) {
  Eigen::VectorXd out(static_cast<int>(dofs.size()));
  for (std::size_t k = 0; k < dofs.size(); ++k) out[k] = v[dofs[k]];
  return out;
}

}  // namespace

LinearModel::LinearModel(const mesh::TetMesh& m, const fem::Material& mat, std::vector<char> c, Eigen::VectorXd g,
                         std::vector<double> node_masses, double alpha, std::vector<char> removed_elements)
    : mesh(&m), material(mat), masses(std::move(node_masses)), damping_alpha(alpha), constrained(std::move(c)),
      gravity_force(std::move(g)), removed(std::move(removed_elements)) {
  if (removed.empty()) {
    K = small_strain_stiffness(m, mat);
    return;
  }
  mesh::TetMesh left;  // the same nodes, the elements a cut left
  left.nodes = m.nodes;
  for (int e = 0; e < m.num_tets(); ++e)
    if (live(e)) left.tets.push_back(m.tets[e]);
  K = small_strain_stiffness(left, mat);
}

ExchangeSecondary::ExchangeSecondary(const LinearModel& model, const PrimaryRegion& region, double step)
    : model_(&model), step_(step) {
  const int n = model.mesh->num_nodes();
  secondary_ = free_dofs(n, model.constrained, [&](int i) { return !region.interior[i]; });
  primary_ = free_dofs(n, model.constrained, [&](int i) { return region.interior[i] != 0; });
  K_sp_ = dof_block(model.K, secondary_, primary_);
  Eigen::SparseMatrix<double> K_ss = dof_block(model.K, secondary_, secondary_);
  const int ns = static_cast<int>(secondary_.size());
  if (dynamic()) {
    if (model.masses.empty()) throw InputError("regions: an implicit-dynamic secondary needs the lumped masses");
    mass_.resize(ns);
    for (int k = 0; k < ns; ++k) mass_[k] = model.masses[secondary_[k] / 3];
    // Newmark, γ = 1/2, β = 1/4: K_eff = K + (4/H² + 2α/H) M.
    const double c = 4.0 / (step * step) + 2.0 * model.damping_alpha / step;
    for (int k = 0; k < ns; ++k) K_ss.coeffRef(k, k) += c * mass_[k];
    u_s_.setZero(ns);
    v_s_.setZero(ns);
    a_s_.setZero(ns);
  }
  solver_.factorize(K_ss, "regions: secondary region (001 eq. 7)");
  u_p_.setZero(static_cast<int>(primary_.size()));
  rhs_.setZero(ns);
}

void ExchangeSecondary::start_at(const double* u) {
  if (!dynamic()) return;
  for (std::size_t k = 0; k < secondary_.size(); ++k) u_s_[k] = u[secondary_[k]];
  v_s_.setZero();
  a_s_.setZero();
}

void ExchangeSecondary::solve(double* u, double gravity_factor) {
  for (std::size_t k = 0; k < primary_.size(); ++k) u_p_[k] = u[primary_[k]];
  rhs_.noalias() = -(K_sp_ * u_p_);
  for (std::size_t k = 0; k < secondary_.size(); ++k) rhs_[k] += gravity_factor * model_->gravity_force[secondary_[k]];
  if (dynamic()) {
    // Newmark's average acceleration: M (4/H² u + 4/H v + a) + α M (2/H u + v) on the right.
    const double H = step_, alpha = model_->damping_alpha;
    rhs_.array() += mass_.array() * ((4.0 / (H * H) + 2.0 * alpha / H) * u_s_.array() +
                                     (4.0 / H + alpha) * v_s_.array() + a_s_.array());
  }
  solver_.solve_in_place(rhs_);
  if (dynamic()) {
    const double H = step_;
    for (std::size_t k = 0; k < secondary_.size(); ++k) {
      const double a_next = 4.0 / (H * H) * (rhs_[k] - u_s_[k]) - 4.0 / H * v_s_[k] - a_s_[k];
      v_s_[k] += 0.5 * H * (a_s_[k] + a_next);
      a_s_[k] = a_next;
      u_s_[k] = rhs_[k];
    }
  }
  for (std::size_t k = 0; k < secondary_.size(); ++k) u[secondary_[k]] = rhs_[k];
}

CondensedSecondary::CondensedSecondary(const LinearModel& model, const PrimaryRegion& region)
    : model_(&model), interface_nodes_(static_cast<int>(region.interface.size())) {
  const mesh::TetMesh& mesh = *model.mesh;
  const int n = mesh.num_nodes();
  // K^s: the secondary elements alone, on the whole node numbering.
  mesh::TetMesh far;
  far.nodes = mesh.nodes;
  std::vector<char> primary(mesh.num_tets(), 0);
  for (int e : region.elements) primary[e] = 1;
  for (int e = 0; e < mesh.num_tets(); ++e)
    if (!primary[e] && model.live(e)) far.tets.push_back(mesh.tets[e]);
  std::vector<char> in_far(n, 0);
  for (const auto& t : far.tets)
    for (int i : t) in_far[i] = 1;
  const Eigen::SparseMatrix<double> Ks = small_strain_stiffness(far, model.material);
  std::vector<int> slot_of_node(n, -1);
  for (std::size_t a = 0; a < region.interface.size(); ++a) slot_of_node[region.interface[a]] = static_cast<int>(a);
  interface_ = free_dofs(n, model.constrained, [&](int i) { return slot_of_node[i] >= 0; });
  secondary_ = free_dofs(n, model.constrained, [&](int i) { return in_far[i] && region.local[i] < 0; });
  for (int d : interface_) interface_slot_.push_back(3 * slot_of_node[d / 3] + d % 3);
  solver_.factorize(dof_block(Ks, secondary_, secondary_), "regions: secondary region (condensation)");
  K_si_ = dof_block(Ks, secondary_, interface_);
  const Eigen::SparseMatrix<double> K_ii = dof_block(Ks, interface_, interface_);
  // S_II = K_II − K_IS K_SS⁻¹ K_SI (K_IS = K_SIᵀ: symmetric), solved for blocks of interface
  // dofs at once (the supernodal solve runs them as matrix products).
  const int ni = static_cast<int>(interface_.size());
  const int ns = static_cast<int>(secondary_.size());
  S_ = Eigen::MatrixXd(K_ii);
  constexpr int kBlock = 64;
  Eigen::MatrixXd X(ns, kBlock);
  for (int j0 = 0; j0 < ni; j0 += kBlock) {
    const int w = std::min(kBlock, ni - j0);
    X.resize(ns, w);
    X = Eigen::MatrixXd(K_si_.middleCols(j0, w));
    solver_.solve_in_place(X);
    S_.middleCols(j0, w).noalias() -= K_si_.transpose() * X;
  }
  S_ = 0.5 * (S_ + S_.transpose()).eval();  // symmetric to round-off, exactly
  g_s_ = gather(model.gravity_force, secondary_);
  Eigen::VectorXd x = g_s_;
  solver_.solve_in_place(x);
  h_ = K_si_.transpose() * x;
  u_i_.setZero(ni);
  f_i_.setZero(ni);
  rhs_.setZero(static_cast<int>(secondary_.size()));
}

void CondensedSecondary::interface_force(const double* u_interface, double gravity_factor, double* force) {
  const int ni = static_cast<int>(interface_.size());
  for (int k = 0; k < ni; ++k) u_i_[k] = u_interface[interface_slot_[k]];
  if (single_precision()) {
    u32_ = u_i_.cast<float>();
    f32_.noalias() = S32_ * u32_;
    f_i_ = f32_.cast<double>();
  } else {
    f_i_.noalias() = S_ * u_i_;
  }
  if (modes() > 0) {
    // The modes' pull on the interface, LᵀΩ² (z − L u_I) (Craig–Bampton in z, header).
    Lu_.noalias() = L_ * u_i_;
    eta_ = z_ - Lu_;
    f_i_.noalias() -= G_ * eta_;
  }
  for (int k = 0; k < ni; ++k) force[interface_slot_[k]] = -f_i_[k] - gravity_factor * h_[k];
}

void CondensedSecondary::use_modes(int count, double dt, double damping_alpha) {
  if (model_->masses.empty()) throw InputError("regions: the far field's modes need the lumped masses");
  const int ns = static_cast<int>(secondary_.size());
  Eigen::VectorXd mass(ns);
  for (int k = 0; k < ns; ++k) mass[k] = model_->masses[secondary_[k] / 3];
  const Eigen::SparseMatrix<double> K_ss = dof_block(model_->K, secondary_, secondary_);
  // model_->K holds the primary elements too, but K_SS over the far field's own dofs sees only
  // far-field elements (a far node touches no primary element).
  FarFieldModes m = lowest_modes(K_ss, mass, solver_, count);
  phi_ = std::move(m.phi);
  omega2_ = std::move(m.omega2);
  // L = Φᵀ M Ψ = −(K_SS⁻¹ M Φ)ᵀ K_SI, computed as written so that it holds for Ritz vectors too.
  Eigen::MatrixXd W = mass.asDiagonal() * phi_;
  solver_.solve_in_place(W);
  L_ = -(W.transpose() * K_si_);
  G_ = L_.transpose() * omega2_.asDiagonal();
  const int mm = modes();
  z_.setZero(mm);
  z_before_.setZero(mm);
  z_next_.setZero(mm);
  Lu_.setZero(mm);
  eta_.setZero(mm);
  const dynamics::CentralDifference cd = dynamics::central_difference(1.0, damping_alpha, dt);
  cd_A_ = cd.A;
  cd_B_ = cd.B;
  cd_C_ = cd.C;
}

void CondensedSecondary::start_modes(const double* u) { start_modes(u, nullptr); }

void CondensedSecondary::start_modes(const double* u, const double* u_before) {
  if (modes() == 0) return;
  auto project = [&](const double* v, Eigen::VectorXd& z) {
    for (int j = 0; j < modes(); ++j) {
      double s = 0;
      for (std::size_t k = 0; k < secondary_.size(); ++k)
        s += phi_(static_cast<int>(k), j) * model_->masses[secondary_[k] / 3] * v[secondary_[k]];
      z[j] = s;
    }
  };
  project(u, z_);
  if (u_before)
    project(u_before, z_before_);
  else
    z_before_ = z_;
}

void CondensedSecondary::recover_previous(double* u_before, double gravity_factor) {
  keep_for_recovery(u_before, gravity_factor);
  if (modes() > 0) kept_z_ = z_before_;
  recover_kept(u_before);
}

void CondensedSecondary::advance_modes() {
  // z_{n+1} = A Ω² (L u_I − z_n) + B z_n − C z_{n−1}: 000 eq. 33 for each unit-mass mode.
  for (int j = 0; j < modes(); ++j)
    z_next_[j] = cd_A_ * omega2_[j] * (Lu_[j] - z_[j]) + cd_B_ * z_[j] - cd_C_ * z_before_[j];
  z_before_.swap(z_);
  z_.swap(z_next_);
}

void CondensedSecondary::use_single_precision() {
  if (single_precision()) return;
  S32_ = S_.cast<float>();
  S_ = Eigen::MatrixXd();
  u32_.setZero(S32_.rows());
  f32_.setZero(S32_.rows());
}

std::vector<double> CondensedSecondary::interface_masses() {
  if (model_->masses.empty()) throw InputError("regions: the far field's inertia needs the lumped masses");
  const int ni = static_cast<int>(interface_.size());
  const int ns = static_cast<int>(secondary_.size());
  std::vector<double> sum(interface_nodes_, 0.0), count(interface_nodes_, 0.0);
  for (int c = 0; c < 3; ++c) {
    // Row sums of Ψᵀ M Ψ for a unit interface translation along c: w = K_SS⁻¹ K_SI e_c (= −Ψ e_c),
    // then Ψᵀ M Ψ e_c = K_IS K_SS⁻¹ (M w).
    Eigen::VectorXd e = Eigen::VectorXd::Zero(ni);
    for (int k = 0; k < ni; ++k)
      if (interface_[k] % 3 == c) e[k] = 1.0;
    Eigen::VectorXd w = K_si_ * e;
    solver_.solve_in_place(w);
    for (int k = 0; k < ns; ++k) w[k] *= model_->masses[secondary_[k] / 3];
    solver_.solve_in_place(w);
    Eigen::VectorXd z = K_si_.transpose() * w;
    // The modes carry LᵀL of it (header): the residual mass is what stays on the interface.
    if (modes() > 0) z -= L_.transpose() * (L_ * e);
    for (int k = 0; k < ni; ++k)
      if (interface_[k] % 3 == c) {
        sum[interface_slot_[k] / 3] += z[k];
        count[interface_slot_[k] / 3] += 1;
      }
  }
  std::vector<double> m(interface_nodes_, 0.0);
  for (int a = 0; a < interface_nodes_; ++a) m[a] = count[a] > 0 ? std::max(0.0, sum[a] / count[a]) : 0.0;
  return m;
}

void CondensedSecondary::recover(double* u, double gravity_factor) {
  keep_for_recovery(u, gravity_factor);
  recover_kept(u);
}

void CondensedSecondary::keep_for_recovery(const double* u, double gravity_factor) {
  const int ni = static_cast<int>(interface_.size());
  if (kept_u_i_.size() != ni) kept_u_i_.setZero(ni);  // sized at the first keep, then reused
  for (int k = 0; k < ni; ++k) kept_u_i_[k] = u[interface_[k]];
  if (modes() > 0) kept_z_ = z_;  // same size every time: no allocation after the first
  kept_gravity_ = gravity_factor;
  kept_ = true;
}

void CondensedSecondary::recover_kept(double* u) {
  if (!kept_) return;
  rhs_.noalias() = kept_gravity_ * g_s_;
  rhs_.noalias() -= K_si_ * kept_u_i_;
  solver_.solve_in_place(rhs_);
  if (modes() > 0) {
    // u_S = Ψ u_I + Φ (z − L u_I): the static shape plus the modes' motion relative to it.
    // (Scratch of its own: Lu_ and eta_ belong to the substep's interface force.)
    kept_Lu_.noalias() = L_ * kept_u_i_;
    kept_z_ -= kept_Lu_;
    rhs_.noalias() += phi_ * kept_z_;
  }
  for (std::size_t k = 0; k < secondary_.size(); ++k) u[secondary_[k]] = rhs_[k];
  kept_ = false;
}

}  // namespace softsim::regions
