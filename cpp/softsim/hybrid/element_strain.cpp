#include "softsim/hybrid/element_strain.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "softsim/fem/element_stress.hpp"
#include "softsim/fem/tet_geometry.hpp"

namespace softsim::hybrid {

double strain_of(const Eigen::Matrix3d& F, StrainMeasure measure) {
  if (measure == StrainMeasure::displacement_gradient) {
    const Eigen::Matrix3d H = F - Eigen::Matrix3d::Identity();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(H.transpose() * H, Eigen::EigenvaluesOnly);
    return std::sqrt(std::max(eig.eigenvalues().maxCoeff(), 0.0));
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(fem::green_lagrange_strain(F), Eigen::EigenvaluesOnly);
  return eig.eigenvalues().cwiseAbs().maxCoeff();
}

std::vector<double> element_strain(const mesh::TetMesh& mesh, const std::vector<double>& u, StrainMeasure measure) {
  if (u.size() != 3 * mesh.nodes.size()) throw std::invalid_argument("element_strain: displacement size");
  std::vector<double> out(mesh.num_tets());
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const fem::TetShape shape = fem::tet_shape(mesh, e);
    out[e] = strain_of(fem::deformation_gradient(shape, fem::corner_displacements(mesh, e, u.data())), measure);
  }
  return out;
}

}  // namespace softsim::hybrid
