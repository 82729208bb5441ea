#include "softsim/fem/tet_geometry.hpp"

#include <Eigen/Dense>

namespace softsim::fem {

TetShape tet_shape(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                   const Eigen::Vector3d& x3) {
  Eigen::Matrix3d D;  // ⁰D_X (000 eq. 5)
  D.col(0) = x1 - x0;
  D.col(1) = x2 - x0;
  D.col(2) = x3 - x0;
  TetShape s;
  s.volume = D.determinant() / 6.0;  // 000 eq. 1
  // b = D⁻¹ (x − x0) are the barycentric weights of corners 1..3 (000 eq. 4), so their
  // gradients are the rows of D⁻¹ and corner 0 takes minus their sum.
  const Eigen::Matrix3d Dinv = D.inverse();
  for (int a = 1; a < 4; ++a) s.grad[a] = Dinv.row(a - 1).transpose();
  s.grad[0] = -(s.grad[1] + s.grad[2] + s.grad[3]);
  return s;
}

TetShape tet_shape(const mesh::TetMesh& mesh, int element) {
  const auto& t = mesh.tets[element];
  return tet_shape(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]);
}

Eigen::Matrix3d deformation_gradient(const TetShape& shape, const Corners& u) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  for (int a = 0; a < 4; ++a) F += u[a] * shape.grad[a].transpose();
  return F;
}

double volume_ratio(const TetShape& shape, const Corners& u) { return deformation_gradient(shape, u).determinant(); }

Corners corner_displacements(const mesh::Tet& tet, const double* u) {
  Corners c;
  for (int a = 0; a < 4; ++a) {
    const int n = tet[a];
    c[a] = Eigen::Vector3d(u[3 * n], u[3 * n + 1], u[3 * n + 2]);
  }
  return c;
}

Corners corner_displacements(const mesh::TetMesh& mesh, int element, const double* u) {
  return corner_displacements(mesh.tets[element], u);
}

}  // namespace softsim::fem
