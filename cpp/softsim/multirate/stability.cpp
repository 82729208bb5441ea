#include "softsim/multirate/stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace softsim::multirate {

double omega_max_bound(const ReducedSystem& system, int dof_begin, int dof_end) {
  // Gershgorin: lambda_max(M^-1/2 K_bb M^-1/2) <= max_i sum_j |K_ij| / sqrt(m_i m_j), j in the block.
  double bound = 0.0;
  for (int i = dof_begin; i < dof_end; ++i) {
    double row = 0.0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(system.stiffness, i); it; ++it) {
      const int j = static_cast<int>(it.col());
      if (j < dof_begin || j >= dof_end) continue;
      row += std::abs(it.value()) / std::sqrt(system.mass[i] * system.mass[j]);
    }
    bound = std::max(bound, row);
  }
  return std::sqrt(bound);
}

double explicit_step_limit(double omega, double alpha, ExplicitVariant variant) {
  if (omega <= 0.0) return std::numeric_limits<double>::infinity();
  if (variant == ExplicitVariant::kCentral) return 2.0 / omega;  // 001 eq. 5, |z| <= 1 for every mode
  return (alpha + std::sqrt(alpha * alpha + 4.0 * omega * omega)) / (omega * omega);  // 001 eq. 6
}

double explicit_step_limit(const ReducedSystem& system, int dof_begin, int dof_end, ExplicitVariant variant) {
  double alpha = std::numeric_limits<double>::infinity();
  for (int i = dof_begin; i < dof_end; ++i) alpha = std::min(alpha, system.damping[i] / system.mass[i]);
  if (dof_end <= dof_begin) alpha = 0.0;
  return explicit_step_limit(omega_max_bound(system, dof_begin, dof_end), alpha, variant);
}

}  // namespace softsim::multirate
