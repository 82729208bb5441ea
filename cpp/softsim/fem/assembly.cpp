#include "softsim/fem/assembly.hpp"

#include <algorithm>

#include <Eigen/Dense>

#include "softsim/fem/element_response.hpp"

namespace softsim::fem {

namespace {
std::vector<TetShape> tet_shapes(const mesh::TetMesh& mesh) {
  std::vector<TetShape> shapes;
  shapes.reserve(mesh.tets.size());
  for (int e = 0; e < mesh.num_tets(); ++e) shapes.push_back(tet_shape(mesh, e));
  return shapes;
}
}  // namespace

Assembler::Assembler(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds, const Material& material)
    : num_nodes_(mesh.num_nodes()),
      tets_(mesh.tets),
      kinds_(kinds),
      material_(material),
      shapes_(tet_shapes(mesh)),
      nodal_pressure_(mesh, kinds, shapes_, material.volumetric_modulus),
      edge_smoothing_(mesh, kinds, shapes_) {
  const int n = 3 * num_nodes_;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(tets_.size() * 144);
  for (const auto& t : tets_)
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        for (int b = 0; b < 4; ++b)
          for (int k = 0; k < 3; ++k) triplets.emplace_back(3 * t[a] + i, 3 * t[b] + k, 0.0);
  std::vector<std::pair<int, int>> coupled = nodal_pressure_.coupled_nodes();
  const std::vector<std::pair<int, int>> edge_coupled = edge_smoothing_.coupled_nodes();
  coupled.insert(coupled.end(), edge_coupled.begin(), edge_coupled.end());
  for (const auto& [b, c] : coupled)
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) triplets.emplace_back(3 * b + i, 3 * c + k, 0.0);
  pattern_.resize(n, n);
  pattern_.setFromTriplets(triplets.begin(), triplets.end());
  pattern_.makeCompressed();
  value_index_.resize(tets_.size() * 144);
  const int* outer = pattern_.outerIndexPtr();
  const int* inner = pattern_.innerIndexPtr();
  for (std::size_t e = 0; e < tets_.size(); ++e) {
    const auto& t = tets_[e];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        for (int b = 0; b < 4; ++b)
          for (int k = 0; k < 3; ++k) {
            const int row = 3 * t[a] + i, col = 3 * t[b] + k;  // column-major storage
            const int* first = inner + outer[col];
            const int* last = inner + outer[col + 1];
            const int* it = std::lower_bound(first, last, row);
            value_index_[e * 144 + (3 * a + i) * 12 + 3 * b + k] = static_cast<int>(it - inner);
          }
  }
}

void Assembler::internal_forces(const double* u, Eigen::VectorXd& f) const {
  f.setZero(3 * num_nodes_);
  for (std::size_t e = 0; e < tets_.size(); ++e) {
    if (kinds_[e] == ElementKind::smoothed) continue;  // edge_smoothing_
    const Corners fe = with_element_material(material_, e, [&](const Material& m) {
      return element_forces(m, kinds_[e], shapes_[e], corner_displacements(tets_[e], u));
    });
    for (int a = 0; a < 4; ++a) f.segment<3>(3 * tets_[e][a]) += fe[a];
  }
  nodal_pressure_.add_forces(u, f);
  edge_smoothing_.add_forces(material_, u, f);
}

void Assembler::tangent(const double* u, Eigen::SparseMatrix<double>& K) const {
  if (K.nonZeros() != pattern_.nonZeros()) K = pattern_;
  double* values = K.valuePtr();
  std::fill(values, values + K.nonZeros(), 0.0);
  for (std::size_t e = 0; e < tets_.size(); ++e) {
    if (kinds_[e] == ElementKind::smoothed) continue;  // edge_smoothing_
    const ElementMatrix Ke = with_element_material(material_, e, [&](const Material& m) {
      return element_tangent(m, kinds_[e], shapes_[e], corner_displacements(tets_[e], u));
    });
    const int* idx = &value_index_[e * 144];
    for (int r = 0; r < 12; ++r)
      for (int c = 0; c < 12; ++c) values[idx[r * 12 + c]] += Ke(r, c);
  }
  nodal_pressure_.add_tangent(u, K);
  edge_smoothing_.add_tangent(material_, u, K);
}

double Assembler::strain_energy(const double* u) const {
  double w = 0;
  for (std::size_t e = 0; e < tets_.size(); ++e)
    if (kinds_[e] != ElementKind::smoothed)
      w += with_element_material(material_, e, [&](const Material& m) {
        return element_energy(m, kinds_[e], shapes_[e], corner_displacements(tets_[e], u));
      });
  return w + nodal_pressure_.energy(u) + edge_smoothing_.energy(material_, u);
}

double Assembler::min_volume_ratio(const double* u, int* element) const {
  double jmin = 1e300;
  for (std::size_t e = 0; e < tets_.size(); ++e) {
    const double J = volume_ratio(shapes_[e], corner_displacements(tets_[e], u));
    if (J < jmin) {
      jmin = J;
      if (element) *element = static_cast<int>(e);
    }
  }
  return jmin;
}

}  // namespace softsim::fem
