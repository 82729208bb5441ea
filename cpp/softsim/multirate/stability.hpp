#pragma once
// The stability limit of the explicit solvers (001 eq. 4 and its exact form for eqs. 5-6).
//
// 001 eq. 4 states the critical step of an elastic continuum, dt <= L_e sqrt(rho / E). For a
// node graph with arbitrary elements we use the discrete form: a mode of circular frequency
// omega and mass-proportional damping alpha = c_i / m_i is stable under
//   eq. 5 (central):           dt <= 2 / omega
//   eq. 6 (backward damping):  dt <= (alpha + sqrt(alpha^2 + 4 omega^2)) / omega^2
// and omega_max is bounded from above by Gershgorin's theorem on M^-1/2 K M^-1/2, so the limit
// we enforce is never above the true one. For the uniform bar both coincide with eq. 4:
// 2 / omega_bound = h / c.
#include "softsim/multirate/linear_model.hpp"
#include "softsim/multirate/solver_spec.hpp"

namespace softsim::multirate {

// Upper bound of the largest circular frequency of the DOF block [dof_begin, dof_end) with
// every other DOF held fixed (the situation of a region solved by 001 eq. 7).
double omega_max_bound(const ReducedSystem& system, int dof_begin, int dof_end);

// The largest stable step of the explicit variant on that block (uses the smallest damping
// ratio alpha = c/m of the block, the conservative choice for eq. 6).
double explicit_step_limit(const ReducedSystem& system, int dof_begin, int dof_end, ExplicitVariant variant);

// The step limit of one mode (omega, alpha), used by the above and by the tests.
double explicit_step_limit(double omega, double alpha, ExplicitVariant variant);

}  // namespace softsim::multirate
