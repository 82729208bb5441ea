#include "softsim/multirate/solver_spec.hpp"

namespace softsim::multirate {

std::string solver_name(const SolverSpec& spec) {
  switch (spec.kind) {
    case SolverKind::kStatic:
      return "static";
    case SolverKind::kImplicit:
      return spec.implicit_scheme == ImplicitScheme::kNewmark ? "implicit/newmark" : "implicit/backward_euler";
    case SolverKind::kExplicit:
      return spec.explicit_variant == ExplicitVariant::kCentral ? "explicit/central" : "explicit/backward_damping";
  }
  return "unknown";
}

}  // namespace softsim::multirate
