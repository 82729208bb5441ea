#include "softsim/fem/edge_smoothing.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace softsim::fem {

namespace {

// The six edges of a tetrahedron as corner pairs.
constexpr int kEdgeCorners[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

// K(row, col) += v for an entry the pattern must already hold.
void add_to_pattern(Eigen::SparseMatrix<double>& K, int row, int col, double v) {
  const int* inner = K.innerIndexPtr();
  const int* first = inner + K.outerIndexPtr()[col];
  const int* last = inner + K.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(first, last, row);
  if (it == last || *it != row) throw std::logic_error("EdgeSmoothing: the tangent pattern lacks an edge coupling");
  K.valuePtr()[it - inner] += v;
}

}  // namespace

EdgeSmoothing::EdgeSmoothing(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds,
                             const std::vector<TetShape>& shapes)
    : tets_(mesh.tets), kinds_(kinds), shapes_(shapes) {
  const int m = mesh.num_tets();
  std::map<std::pair<int, int>, std::vector<int>> around;  // edge (lo, hi) → its smoothed elements
  for (int e = 0; e < m; ++e)
    if (kinds[e] == ElementKind::smoothed)
      for (const auto& c : kEdgeCorners) {
        const int a = mesh.tets[e][c[0]], b = mesh.tets[e][c[1]];
        around[{std::min(a, b), std::max(a, b)}].push_back(e);
      }
  element_edges_.assign(m, {-1, -1, -1, -1, -1, -1});
  node_edge_begin_.assign(mesh.num_nodes() + 1, 0);
  edge_begin_.push_back(0);
  std::map<std::pair<int, int>, int> index;
  for (const auto& [edge, elements] : around) {  // ascending (lo, hi): grouped by the lower node
    index[edge] = static_cast<int>(edge_nodes_.size());
    edge_nodes_.push_back({edge.first, edge.second});
    ++node_edge_begin_[edge.first + 1];
    double v = 0;
    for (int e : elements) v += shapes[e].volume / 6.0;
    edge_volume_.push_back(v);
    for (int e : elements) {
      edge_element_.push_back(e);
      edge_weight_.push_back(shapes[e].volume / 6.0 / v);
    }
    edge_begin_.push_back(static_cast<int>(edge_element_.size()));
  }
  for (int a = 0; a < mesh.num_nodes(); ++a) node_edge_begin_[a + 1] += node_edge_begin_[a];
  for (int e = 0; e < m; ++e)
    if (kinds[e] == ElementKind::smoothed)
      for (int j = 0; j < 6; ++j) {
        const int a = mesh.tets[e][kEdgeCorners[j][0]], b = mesh.tets[e][kEdgeCorners[j][1]];
        element_edges_[e][j] = index.at({std::min(a, b), std::max(a, b)});
      }
}

void EdgeSmoothing::smoothed_gradients(const Eigen::Matrix3d* F, int begin, int end, Eigen::Matrix3d* Fk) const {
  for (int k = begin; k < end; ++k) {
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    for (int p = edge_begin_[k]; p < edge_begin_[k + 1]; ++p) s += edge_weight_[p] * F[edge_element_[p]];
    Fk[k] = s;
  }
}

void EdgeSmoothing::edge_stresses(const Material& m, const Eigen::Matrix3d* F, int begin, int end,
                                  Eigen::Matrix3d* P) const {
  for (int k = begin; k < end; ++k) {
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    for (int p = edge_begin_[k]; p < edge_begin_[k + 1]; ++p) s += edge_weight_[p] * F[edge_element_[p]];
    // A law with per-element fibres: the domain takes the fibre of its first element.
    P[k] = with_element_material(m, edge_element_[edge_begin_[k]],
                                 [&](const Material& me) { return first_piola(me, ElementKind::smoothed, s); });
  }
}

Eigen::Matrix3d EdgeSmoothing::element_stress(int e, const Eigen::Matrix3d* P) const {
  const auto& k = element_edges_[e];
  return (P[k[0]] + P[k[1]] + P[k[2]] + P[k[3]] + P[k[4]] + P[k[5]]) / 6.0;
}

std::vector<Eigen::Matrix3d> EdgeSmoothing::element_gradients(const double* u) const {
  std::vector<Eigen::Matrix3d> F(tets_.size(), Eigen::Matrix3d::Identity());
  for (std::size_t e = 0; e < tets_.size(); ++e)
    if (kinds_[e] == ElementKind::smoothed) F[e] = deformation_gradient(shapes_[e], corner_displacements(tets_[e], u));
  return F;
}

void EdgeSmoothing::add_forces(const Material& m, const double* u, Eigen::VectorXd& f) const {
  if (empty()) return;
  const std::vector<Eigen::Matrix3d> F = element_gradients(u);
  std::vector<Eigen::Matrix3d> P(edge_nodes_.size());
  edge_stresses(m, F.data(), 0, num_edges(), P.data());
  for (std::size_t e = 0; e < tets_.size(); ++e) {
    if (kinds_[e] != ElementKind::smoothed) continue;
    const Eigen::Matrix3d Pe = shapes_[e].volume * element_stress(static_cast<int>(e), P.data());
    for (int a = 0; a < 4; ++a) f.segment<3>(3 * tets_[e][a]) += Pe * shapes_[e].grad[a];
  }
}

double EdgeSmoothing::energy(const Material& m, const double* u) const {
  if (empty()) return 0.0;
  const std::vector<Eigen::Matrix3d> F = element_gradients(u);
  std::vector<Eigen::Matrix3d> Fk(edge_nodes_.size());
  smoothed_gradients(F.data(), 0, num_edges(), Fk.data());
  double w = 0;
  for (int k = 0; k < num_edges(); ++k)
    w += edge_volume_[k] * with_element_material(m, edge_element_[edge_begin_[k]], [&](const Material& me) {
           return energy_density(me, ElementKind::smoothed, Fk[k]);
         });
  return w;
}

double EdgeSmoothing::element_energy(const Material& m, int e, const double* u) const {
  double w = 0;
  for (int k : element_edges_[e]) {
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    for (int p = edge_begin_[k]; p < edge_begin_[k + 1]; ++p) {
      const int d = edge_element_[p];
      s += edge_weight_[p] * deformation_gradient(shapes_[d], corner_displacements(tets_[d], u));
    }
    w += shapes_[e].volume / 6.0 * with_element_material(m, edge_element_[edge_begin_[k]], [&](const Material& me) {
           return energy_density(me, ElementKind::smoothed, s);
         });
  }
  return w;
}

void EdgeSmoothing::domain_gradients(int k, std::vector<int>& nodes, std::vector<Eigen::Vector3d>& G) const {
  nodes.clear();
  G.clear();
  for (int p = edge_begin_[k]; p < edge_begin_[k + 1]; ++p) {
    const int e = edge_element_[p];
    for (int c = 0; c < 4; ++c) {
      const Eigen::Vector3d g = edge_weight_[p] * shapes_[e].grad[c];
      const auto it = std::find(nodes.begin(), nodes.end(), tets_[e][c]);
      if (it == nodes.end()) {
        nodes.push_back(tets_[e][c]);
        G.push_back(g);
      } else {
        G[it - nodes.begin()] += g;
      }
    }
  }
}

std::vector<std::pair<int, int>> EdgeSmoothing::coupled_nodes() const {
  std::vector<std::pair<int, int>> pairs;
  std::vector<int> nodes;
  std::vector<Eigen::Vector3d> G;
  for (int k = 0; k < num_edges(); ++k) {
    domain_gradients(k, nodes, G);
    for (int b : nodes)
      for (int c : nodes) pairs.emplace_back(b, c);
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

void EdgeSmoothing::add_tangent(const Material& m, const double* u, Eigen::SparseMatrix<double>& K) const {
  if (empty()) return;
  const std::vector<Eigen::Matrix3d> F = element_gradients(u);
  std::vector<Eigen::Matrix3d> Fk(edge_nodes_.size());
  smoothed_gradients(F.data(), 0, num_edges(), Fk.data());
  std::vector<int> nodes;
  std::vector<Eigen::Vector3d> G;
  for (int k = 0; k < num_edges(); ++k) {
    domain_gradients(k, nodes, G);
    const Material me = m.fibres ? m.for_element(edge_element_[edge_begin_[k]]) : m;
    const FirstPiolaLinearisation lin(me, ElementKind::smoothed, Fk[k]);
    const std::size_t q = nodes.size();
    for (std::size_t b = 0; b < q; ++b)
      for (int i = 0; i < 3; ++i) {
        // ∂F_k/∂u_{b,i} = e_i ⊗ G_b; the force on node a is V_k dP G_a.
        const Eigen::Matrix3d dP = edge_volume_[k] * lin.increment(Eigen::Vector3d::Unit(i) * G[b].transpose());
        for (std::size_t a = 0; a < q; ++a) {
          const Eigen::Vector3d col = dP * G[a];
          for (int r = 0; r < 3; ++r) add_to_pattern(K, 3 * nodes[a] + r, 3 * nodes[b] + i, col[r]);
        }
      }
  }
}

}  // namespace softsim::fem
