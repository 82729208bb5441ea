#include "softsim/hybrid/small_strain_check.hpp"

namespace softsim::hybrid {

StrainMeasure small_strain_measure(fem::ElementKind kind) {
  return kind == fem::ElementKind::corotational ? StrainMeasure::green_lagrange : StrainMeasure::displacement_gradient;
}

SmallStrainCheck::SmallStrainCheck(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds)
    : mesh_(&mesh) {
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const fem::ElementKind k = kinds[e];
    if (!fem::kElementKinds[static_cast<int>(k)].small_strain) continue;
    elements_.push_back(e);
    shapes_.push_back(fem::tet_shape(mesh, e));
    measures_.push_back(small_strain_measure(k));
  }
  record_.elements = static_cast<int>(elements_.size());
}

}  // namespace softsim::hybrid
