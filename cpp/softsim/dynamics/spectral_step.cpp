#include "softsim/dynamics/spectral_step.hpp"

#include <cmath>
#include <random>
#include <sstream>

#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/fem/assembly.hpp"
#include "softsim/io/errors.hpp"

namespace softsim::dynamics {

SpectralStep power_iteration_step(const Eigen::SparseMatrix<double>& K, const std::vector<double>& mass,
                                  const std::vector<char>& constrained, const PowerIterationOptions& options) {
  const Eigen::Index n = K.rows();
  if (K.cols() != n || static_cast<Eigen::Index>(3 * mass.size()) != n ||
      static_cast<Eigen::Index>(constrained.size()) != n)
    throw std::invalid_argument("power_iteration_step: K, mass and mask sizes differ");
  // D = M^(−1/2) on the free dofs, 0 on the others: A = D K D has the free system's eigenvalues
  // (and zeros for the removed dofs, which the largest one does not see).
  Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
  for (Eigen::Index q = 0; q < n; ++q)
    if (!constrained[q] && mass[q / 3] > 0) d[q] = 1.0 / std::sqrt(mass[q / 3]);
  std::mt19937 rng(options.seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd x(n);
  for (Eigen::Index q = 0; q < n; ++q) x[q] = d[q] != 0 ? uniform(rng) : 0.0;
  if (!(x.norm() > 0)) throw NumericalError("critical step (power iteration): every degree of freedom is constrained");
  x.normalize();
  SpectralStep s;
  s.tolerance = options.tolerance;
  Eigen::VectorXd y(n);
  for (int it = 1; it <= options.max_iterations; ++it) {
    y = d.cwiseProduct(K * d.cwiseProduct(x));
    s.rayleigh = x.dot(y);
    s.residual = (y - s.rayleigh * x).norm();
    s.iterations = it;
    if (!std::isfinite(s.rayleigh) || !std::isfinite(s.residual))
      throw NumericalError("critical step (power iteration): the stiffness has a non-finite entry");
    if (s.rayleigh > 0 && s.residual <= options.tolerance * s.rayleigh) {
      s.converged = true;
      break;
    }
    const double norm = y.norm();
    if (!(norm > 0)) break;
    x = y / norm;
  }
  if (!(s.rayleigh > 0)) {
    std::ostringstream msg;
    msg << "critical step (power iteration): the free system has no positive stiffness (Rayleigh quotient "
        << s.rayleigh << " after " << s.iterations << " iterations)";
    throw NumericalError(msg.str());
  }
  s.omega_max = std::sqrt(s.rayleigh + s.residual);
  s.dt = 2.0 / s.omega_max;
  return s;
}

SpectralStep power_iteration_step(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds,
                                  const fem::Material& material, const Scene& scene, const double* u,
                                  const PowerIterationOptions& options) {
  const fem::Assembler assembler(mesh, kinds, material);
  Eigen::SparseMatrix<double> K = assembler.pattern();
  const std::vector<double> rest(u ? 0 : 3 * static_cast<std::size_t>(mesh.num_nodes()), 0.0);
  assembler.tangent(u ? u : rest.data(), K);
  const std::vector<char> mask = constrained_mask(resolve_constraints(scene, mesh.num_nodes()), mesh.num_nodes());
  return power_iteration_step(K, lumped_mass(mesh, material.elastic.density), mask, options);
}

}  // namespace softsim::dynamics
