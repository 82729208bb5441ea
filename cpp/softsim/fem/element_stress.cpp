#include "softsim/fem/element_stress.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

namespace softsim::fem {

namespace {
std::vector<TetShape> shapes_of(const mesh::TetMesh& mesh) {
  std::vector<TetShape> shapes(mesh.tets.size());
  for (int e = 0; e < mesh.num_tets(); ++e) shapes[e] = tet_shape(mesh, e);
  return shapes;
}

std::vector<ElementKind> one_per_element(std::vector<ElementKind> kinds, const mesh::TetMesh& mesh) {
  if (kinds.size() != mesh.tets.size()) throw std::invalid_argument("ElementStress: one kind per element");
  return kinds;
}
}  // namespace

Eigen::Matrix3d green_lagrange_strain(const Eigen::Matrix3d& F) {
  return 0.5 * (F.transpose() * F - Eigen::Matrix3d::Identity());
}

Eigen::Matrix3d cauchy_stress(const Material& m, ElementKind kind, const Eigen::Matrix3d& F, double anp_pressure) {
  const Eigen::Matrix3d P = first_piola(m, kind, F);
  if (kind == ElementKind::linear) return P;
  Eigen::Matrix3d sigma = P * F.transpose() / F.determinant();
  if (volumetric_at_nodes(kind)) sigma.diagonal().array() += anp_pressure;
  return 0.5 * (sigma + sigma.transpose());
}

double von_mises_stress(const Eigen::Matrix3d& sigma) {
  const Eigen::Matrix3d s = sigma - sigma.trace() / 3.0 * Eigen::Matrix3d::Identity();
  return std::sqrt(1.5 * s.squaredNorm());
}

ElementStress::ElementStress(const mesh::TetMesh& mesh, std::vector<ElementKind> kinds, const Material& material)
    : material_(material),
      tets_(mesh.tets),
      kinds_(one_per_element(std::move(kinds), mesh)),
      shapes_(shapes_of(mesh)),
      pressure_(mesh, kinds_, shapes_, material.volumetric_modulus),
      pbar_(mesh.tets.size(), 0.0),
      strain_(mesh.tets.size()),
      stress_(mesh.tets.size()),
      von_mises_(mesh.tets.size()) {}

void ElementStress::evaluate(const double* u) {
  if (!pressure_.empty()) pressure_.element_pressures(u, pbar_);
  for (std::size_t e = 0; e < tets_.size(); ++e) {
    const Eigen::Matrix3d F = deformation_gradient(shapes_[e], corner_displacements(tets_[e], u));
    strain_[e] = green_lagrange_strain(F);
    stress_[e] = with_element_material(material_, e, [&](const Material& m) { return cauchy_stress(m, kinds_[e], F, pbar_[e]); });
    von_mises_[e] = von_mises_stress(stress_[e]);
  }
}

}  // namespace softsim::fem
