#pragma once
// Global stiffness and load vectors of the RPIM Galerkin weak form (002 eqs. 19–27):
//   K_IJ = Σ_g w_g B_Iᵀ D B_J    over the Gauss points g whose support holds I and J (eq. 19–22)
//   F^b_I = Σ_g w_g φ_I b(x_g)                                                        (eq. 24)
// Degrees of freedom are node-major: dof 3 I + a is component a of node I.
//
// The assembly gathers per block row (node I) rather than scattering per Gauss point, so the
// parallel loop has no shared writes and the sums are bit-identical for any thread count.
#include <functional>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "softsim/meshless/elasticity.hpp"
#include "softsim/meshless/shape_table.hpp"

namespace softsim::meshless {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// The full symmetric K (both triangles stored), 3N × 3N.
SparseMatrix assemble_stiffness(const ShapeTable& table, int num_nodes, const LameParameters& material);

using BodyForceField = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;  // N/m³
Eigen::VectorXd assemble_body_force(const ShapeTable& table, int num_nodes, const BodyForceField& b);

}  // namespace softsim::meshless
