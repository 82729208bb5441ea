#pragma once
// Reference-configuration geometry of a linear tetrahedron: volume (000 eq. 1) and the
// constant shape-function gradients ∂hᵢ/∂⁰x (000 eqs. 19–22). For the 4-node tetrahedron
// the isoparametric route of eq. 22 and the barycentric route of eqs. 4–5 (rows of ⁰D_X⁻¹)
// give the same constant gradients; the latter is used.
#include <array>

#include <Eigen/Core>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::fem {

using Corners = std::array<Eigen::Vector3d, 4>;

struct TetShape {
  Corners grad;       // ∇N_a in the reference configuration (1/m); they sum to zero
  double volume = 0;  // ⁰V (m³), positive for a positively oriented tet
};

TetShape tet_shape(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                   const Eigen::Vector3d& x3);
TetShape tet_shape(const mesh::TetMesh& mesh, int element);

// F = I + Σ_a u_a ⊗ ∇N_a from the corner displacements.
Eigen::Matrix3d deformation_gradient(const TetShape& shape, const Corners& u);
// The volume ratio J = det F (current over reference volume) of the reference (non-vectorised)
// element functions, the static solver and the failure checks.
double volume_ratio(const TetShape& shape, const Corners& u);

// The corner displacements of a tetrahedron from a nodal field of 3 n values (x, y, z per node).
Corners corner_displacements(const mesh::Tet& tet, const double* u);
Corners corner_displacements(const mesh::TetMesh& mesh, int element, const double* u);

}  // namespace softsim::fem
