#pragma once
// Per-element strain of a displacement field, for the strain-driven partition: elements that a
// reference solution strains beyond a threshold need the nonlinear formulation.
#include <vector>

#include <Eigen/Core>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::hybrid {

enum class StrainMeasure {
  displacement_gradient,  // ‖∇u‖₂ (largest singular value of F − I): strain and rotation, both of
                          // which a small-strain element gets wrong
  green_lagrange,         // largest |principal value| of E = (FᵀF − I)/2: rotation-free strain
};

// The measure of one element's deformation gradient F.
double strain_of(const Eigen::Matrix3d& F, StrainMeasure measure);

// One value per element; u holds 3 values per node.
std::vector<double> element_strain(const mesh::TetMesh& mesh, const std::vector<double>& u, StrainMeasure measure);

}  // namespace softsim::hybrid
