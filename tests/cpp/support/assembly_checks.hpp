#pragma once
// Checks of an element formulation through the reference assembly, shared by the tests of the
// law-driven kinds (ANP, smoothed): a rough non-homogeneous state, and the consistency of the
// energy, the internal forces and the tangent at it.
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <gtest/gtest.h>

#include "softsim/fem/assembly.hpp"
#include "softsim/mesh/tet_mesh.hpp"

#include "support/fields.hpp"

namespace softsim::test_scenes {

// A non-homogeneous state: stretch and shear plus random nodal noise (J from about 0.8 to 1.2).
inline std::vector<double> rough_field(const mesh::TetMesh& m, unsigned seed, double noise) {
  Eigen::Matrix3d F;
  F << 1.08, 0.06, -0.05, 0.03, 0.9, 0.04, -0.07, 0.02, 0.95;
  std::vector<double> u = affine_field(m, F);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-noise, noise);
  for (double& x : u) x += d(rng);
  return u;
}

// The internal forces at u are the gradient of the strain energy and the assembled tangent is
// their derivative: both against central differences along one random direction.
inline void expect_forces_are_the_energy_gradient_and_the_tangent_their_derivative(const fem::Assembler& as,
                                                                                 const std::vector<double>& u) {
  Eigen::VectorXd f;
  as.internal_forces(u.data(), f);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  Eigen::VectorXd v(u.size());
  for (auto& x : v) x = d(rng);
  const double h = 1e-7;
  std::vector<double> up = u, um = u;
  for (std::size_t q = 0; q < u.size(); ++q) up[q] += h * v[q], um[q] -= h * v[q];
  const double dW = (as.strain_energy(up.data()) - as.strain_energy(um.data())) / (2 * h);
  EXPECT_NEAR(dW, f.dot(v), 1e-6 * std::abs(f.dot(v)));

  Eigen::SparseMatrix<double> K = as.pattern();
  as.tangent(u.data(), K);
  Eigen::VectorXd fp, fm;
  const double g = 1e-6;
  for (std::size_t q = 0; q < u.size(); ++q) up[q] = u[q] + g * v[q], um[q] = u[q] - g * v[q];
  as.internal_forces(up.data(), fp);
  as.internal_forces(um.data(), fm);
  const Eigen::VectorXd fd = (fp - fm) / (2 * g);
  EXPECT_LT((K * v - fd).norm(), 1e-6 * fd.norm());
}

}  // namespace softsim::test_scenes
