#pragma once
// Reference (one element at a time, clear rather than fast) element quantities: the corner
// forces Fₐ = ⁰V P ∇Nₐ (000 eq. 13 written with P = F S), the strain energy ⁰V W and the
// 12 × 12 consistent tangent ∂Fₐ/∂u_b. The hot explicit loop (element_set) is tested against
// these; the static Newton solver assembles them.
#include <Eigen/Core>

#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/tet_geometry.hpp"

namespace softsim::fem {

using ElementMatrix = Eigen::Matrix<double, 12, 12>;

// Internal (resisting) corner forces for corner displacements u.
Corners element_forces(const Material& m, ElementKind kind, const TetShape& shape, const Corners& u);
double element_energy(const Material& m, ElementKind kind, const TetShape& shape, const Corners& u);
// K[3a+i][3b+k] = ∂F_{a,i}/∂u_{b,k} = ⁰V Σ_{J,L} ∇N_{a,J} (∂P_{iJ}/∂F_{kL}) ∇N_{b,L}.
ElementMatrix element_tangent(const Material& m, ElementKind kind, const TetShape& shape, const Corners& u);

}  // namespace softsim::fem
