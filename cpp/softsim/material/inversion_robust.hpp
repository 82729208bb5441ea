#pragma once
// Whether a hyperelastic law (hyperelastic.hpp) is defined, smooth and restoring for inverted
// deformations (J = det F ≤ 0). For such a law an inverted element is a state like any other:
// the explicit kernels compute its forces and the engine does not report it as a failure. For
// every other law (ln J, J^(−2/3): singular at J = 0) an inverted element is a numerical
// failure. A law says it is robust by specialising the trait to true next to its struct
// (stable_neo_hookean.hpp); the default is false, so a new law changes nothing here.
namespace softsim::material {

template <class Law>
inline constexpr bool kInversionRobust = false;

}  // namespace softsim::material
