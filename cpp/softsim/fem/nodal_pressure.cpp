#include "softsim/fem/nodal_pressure.hpp"

#include <algorithm>
#include <stdexcept>

#include <Eigen/Dense>

namespace softsim::fem {

Eigen::Matrix3d cofactor(const Eigen::Matrix3d& F) {
  Eigen::Matrix3d c;
  c.col(0) = F.col(1).cross(F.col(2));
  c.col(1) = F.col(2).cross(F.col(0));
  c.col(2) = F.col(0).cross(F.col(1));
  return c;  // rows of F⁻¹ times J, arranged as J F⁻ᵀ
}

Eigen::Matrix3d cofactor_increment(const Eigen::Matrix3d& F, const Eigen::Matrix3d& dF) {
  // cof F is quadratic in F: d(cof F)[dF] = cof(F + dF) − cof F − cof dF, exactly.
  return cofactor(F + dF) - cofactor(F) - cofactor(dF);
}

NodalPressure::NodalPressure(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds,
                             const std::vector<TetShape>& shapes, double kappa)
    : tets_(mesh.tets), kinds_(kinds), shapes_(shapes), kappa_(kappa) {
  std::vector<double> volume(shapes.size());
  for (std::size_t e = 0; e < shapes.size(); ++e) volume[e] = shapes[e].volume;
  nodal_ = nodal_volumes(mesh, kinds, volume);
  empty_ = nodal_.element.empty();
}

std::vector<Eigen::Matrix3d> NodalPressure::anp_gradients(const double* u) const {
  std::vector<Eigen::Matrix3d> F(tets_.size());
  for (std::size_t e = 0; e < tets_.size(); ++e)
    if (volumetric_at_nodes(kinds_[e])) F[e] = deformation_gradient(shapes_[e], corner_displacements(tets_[e], u));
  return F;
}

void NodalPressure::nodal_volume_ratios(const double* u, std::vector<double>& J) const {
  nodal_volume_ratios(anp_gradients(u), J);
}

void NodalPressure::nodal_volume_ratios(const std::vector<Eigen::Matrix3d>& F, std::vector<double>& J) const {
  std::vector<double> je(tets_.size(), 1.0);
  for (std::size_t e = 0; e < tets_.size(); ++e)
    if (volumetric_at_nodes(kinds_[e])) je[e] = F[e].determinant();
  const int n = static_cast<int>(nodal_.volume.size());
  J.assign(n, 1.0);
  for (int a = 0; a < n; ++a)
    if (nodal_.has_elements(a)) J[a] = nodal_volume_ratio(nodal_, a, je.data());
}

void NodalPressure::element_pressures(const double* u, std::vector<double>& pbar) const {
  std::vector<double> J;
  nodal_volume_ratios(u, J);
  element_pressures(J, pbar);
}

void NodalPressure::element_pressures(const std::vector<double>& J, std::vector<double>& pbar) const {
  pbar.assign(tets_.size(), 0.0);
  for (std::size_t e = 0; e < tets_.size(); ++e)
    if (volumetric_at_nodes(kinds_[e])) {
      double s = 0;
      for (int a : tets_[e]) s += kappa_ * (J[a] - 1.0);  // p_a = U'(J_a)
      pbar[e] = 0.25 * s;
    }
}

void NodalPressure::add_forces(const double* u, Eigen::VectorXd& f) const {
  if (empty_) return;
  const std::vector<Eigen::Matrix3d> F = anp_gradients(u);
  std::vector<double> J, pbar;
  nodal_volume_ratios(F, J);
  element_pressures(J, pbar);
  for (std::size_t e = 0; e < tets_.size(); ++e) {
    if (!volumetric_at_nodes(kinds_[e])) continue;
    const Eigen::Matrix3d P = shapes_[e].volume * pbar[e] * cofactor(F[e]);
    for (int a = 0; a < 4; ++a) f.segment<3>(3 * tets_[e][a]) += P * shapes_[e].grad[a];
  }
}

double NodalPressure::energy(const double* u) const {
  if (empty_) return 0.0;
  std::vector<double> J;
  nodal_volume_ratios(u, J);
  // Over every node (J = 1 adds nothing): the compiler vectorises this loop's products and adds
  // them unfused, so it rounds differently from ElementSet's sum over the ANP nodes only.
  double w = 0;
  for (std::size_t a = 0; a < J.size(); ++a) w += nodal_.volume[a] * 0.5 * kappa_ * (J[a] - 1.0) * (J[a] - 1.0);
  return w;
}

std::vector<std::pair<int, int>> NodalPressure::coupled_nodes() const {
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> patch;
  const int n = static_cast<int>(nodal_.volume.size());
  for (int a = 0; a < n; ++a) {
    patch.clear();
    for (int p = nodal_.begin[a]; p < nodal_.begin[a + 1]; ++p)
      for (int b : tets_[nodal_.element[p]]) patch.push_back(b);
    std::sort(patch.begin(), patch.end());
    patch.erase(std::unique(patch.begin(), patch.end()), patch.end());
    for (int b : patch)
      for (int c : patch) pairs.emplace_back(b, c);
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

namespace {

// K(row, col) += v for an entry the pattern must already hold.
void add_entry(Eigen::SparseMatrix<double>& K, int row, int col, double v) {
  const int* inner = K.innerIndexPtr();
  const int* first = inner + K.outerIndexPtr()[col];
  const int* last = inner + K.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(first, last, row);
  if (it == last || *it != row) throw std::logic_error("NodalPressure: the tangent pattern lacks an ANP coupling");
  K.valuePtr()[it - inner] += v;
}

}  // namespace

void NodalPressure::add_tangent(const double* u, Eigen::SparseMatrix<double>& K) const {
  if (empty_) return;
  const int m = static_cast<int>(tets_.size());
  const std::vector<Eigen::Matrix3d> F = anp_gradients(u);
  std::vector<Eigen::Matrix3d> cof(m);
  for (int e = 0; e < m; ++e)
    if (volumetric_at_nodes(kinds_[e])) cof[e] = cofactor(F[e]);
  std::vector<double> J;
  nodal_volume_ratios(F, J);
  const int n = static_cast<int>(J.size());
  // Element term: ⁰V_e p̄_e d(cof F_e)[e_k ⊗ ∇N_b] ∇N_a.
  for (int e = 0; e < m; ++e) {
    if (!volumetric_at_nodes(kinds_[e])) continue;
    const TetShape& sh = shapes_[e];
    double pbar = 0;
    for (int a : tets_[e]) pbar += 0.25 * kappa_ * (J[a] - 1.0);
    for (int b = 0; b < 4; ++b)
      for (int k = 0; k < 3; ++k) {
        const Eigen::Matrix3d dF = Eigen::Vector3d::Unit(k) * sh.grad[b].transpose();
        const Eigen::Matrix3d dP = sh.volume * pbar * cofactor_increment(F[e], dF);
        for (int a = 0; a < 4; ++a) {
          const Eigen::Vector3d col = dP * sh.grad[a];
          for (int i = 0; i < 3; ++i) add_entry(K, 3 * tets_[e][a] + i, 3 * tets_[e][b] + k, col[i]);
        }
      }
  }
  // Nodal term: V_a κ g_a g_aᵀ with g_a = ∂J_a/∂u = Σ_e w_ae cof F_e ∇N (over e's corners).
  std::vector<int> nodes;
  std::vector<Eigen::Vector3d> g;
  for (int a = 0; a < n; ++a) {
    if (!nodal_.has_elements(a)) continue;
    nodes.clear();
    g.clear();
    for (int p = nodal_.begin[a]; p < nodal_.begin[a + 1]; ++p) {
      const int e = nodal_.element[p];
      for (int c = 0; c < 4; ++c) {
        const Eigen::Vector3d v = nodal_.weight[p] * (cof[e] * shapes_[e].grad[c]);
        const auto it = std::find(nodes.begin(), nodes.end(), tets_[e][c]);
        if (it == nodes.end()) {
          nodes.push_back(tets_[e][c]);
          g.push_back(v);
        } else {
          g[it - nodes.begin()] += v;
        }
      }
    }
    const double scale = nodal_.volume[a] * kappa_;
    for (std::size_t b = 0; b < nodes.size(); ++b)
      for (std::size_t c = 0; c < nodes.size(); ++c)
        for (int i = 0; i < 3; ++i)
          for (int k = 0; k < 3; ++k) add_entry(K, 3 * nodes[b] + i, 3 * nodes[c] + k, scale * g[b][i] * g[c][k]);
  }
}

}  // namespace softsim::fem
