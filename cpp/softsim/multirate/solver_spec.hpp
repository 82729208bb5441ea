#pragma once
// The three solvers of 001 §4, selectable per region, and their variants.
#include <string>

namespace softsim::multirate {

enum class SolverKind {
  kStatic,    // K u = f: no inertia, no damping
  kImplicit,  // implicit dynamic, unconditionally stable (001 eq. 3: (K + C/dt + M/dt^2) u+ = ...)
  kExplicit,  // explicit dynamic on the lumped mass, conditionally stable (001 eqs. 4-6)
};

enum class ImplicitScheme {
  kNewmark,        // Newmark average acceleration (beta = 1/4, gamma = 1/2; the trapezoidal rule): second order, no numerical damping
  kBackwardEuler,  // backward Euler, (K + C/h + M/h^2) u+ = f + M/h^2 (u + h v) + C/h u: first order, dissipative
};

enum class ExplicitVariant {
  kCentral,          // 001 eq. 5: central differences for velocity and acceleration
  kBackwardDamping,  // 001 eq. 6: explicit stiffness, damping taken implicitly (backward difference)
};

// How the static and implicit systems are factorised (once, in setup).
enum class LinearSolverKind {
  kSparse,  // sparse Cholesky after a fill-reducing (AMD) ordering
  kDense,   // dense Cholesky: the direct elimination of 001 §4 on a small model
};

struct SolverSpec {
  SolverKind kind = SolverKind::kImplicit;
  ImplicitScheme implicit_scheme = ImplicitScheme::kBackwardEuler;  // 001 eq. 3 as we read it
  ExplicitVariant explicit_variant = ExplicitVariant::kCentral;
};

std::string solver_name(const SolverSpec& spec);  // "static", "implicit/newmark", "explicit/central", ...

}  // namespace softsim::multirate
