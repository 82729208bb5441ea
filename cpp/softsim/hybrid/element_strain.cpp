#include "softsim/hybrid/element_strain.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "softsim/fem/element_stress.hpp"
#include "softsim/fem/tet_geometry.hpp"

namespace softsim::hybrid {

std::vector<double> element_strain(const mesh::TetMesh& mesh, const std::vector<double>& u, StrainMeasure measure) {
  if (u.size() != 3 * mesh.nodes.size()) throw std::invalid_argument("element_strain: displacement size");
  std::vector<double> out(mesh.num_tets());
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const fem::TetShape shape = fem::tet_shape(mesh, e);
    const Eigen::Matrix3d F = fem::deformation_gradient(shape, fem::corner_displacements(mesh, e, u.data()));
    if (measure == StrainMeasure::displacement_gradient) {
      const Eigen::Matrix3d H = F - Eigen::Matrix3d::Identity();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(H.transpose() * H, Eigen::EigenvaluesOnly);
      out[e] = std::sqrt(std::max(eig.eigenvalues().maxCoeff(), 0.0));
    } else {
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(fem::green_lagrange_strain(F), Eigen::EigenvaluesOnly);
      out[e] = eig.eigenvalues().cwiseAbs().maxCoeff();
    }
  }
  return out;
}

}  // namespace softsim::hybrid
