#include "softsim/fem/element_response.hpp"

namespace softsim::fem {

Corners element_forces(const Material& m, ElementKind kind, const TetShape& shape, const Corners& u) {
  const Eigen::Matrix3d P = first_piola(m, kind, deformation_gradient(shape, u));
  Corners f;
  for (int a = 0; a < 4; ++a) f[a] = shape.volume * P * shape.grad[a];
  return f;
}

double element_energy(const Material& m, ElementKind kind, const TetShape& shape, const Corners& u) {
  return shape.volume * energy_density(m, kind, deformation_gradient(shape, u));
}

ElementMatrix element_tangent(const Material& m, ElementKind kind, const TetShape& shape, const Corners& u) {
  const FirstPiolaLinearisation at(m, kind, deformation_gradient(shape, u));
  ElementMatrix K;
  // Column (b, k): the force response to a unit displacement of corner b along k, whose
  // deformation-gradient increment is e_k ⊗ ∇N_b.
  for (int b = 0; b < 4; ++b)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Matrix3d dF = Eigen::Vector3d::Unit(k) * shape.grad[b].transpose();
      const Eigen::Matrix3d dP = at.increment(dF);
      for (int a = 0; a < 4; ++a) K.block<3, 1>(3 * a, 3 * b + k) = shape.volume * dP * shape.grad[a];
    }
  return K;
}

}  // namespace softsim::fem
