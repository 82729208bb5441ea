#pragma once
// The element formulations an element can be given (000 §2.2.2 plus the corotational and
// average-nodal-pressure variants): chosen per element by the partition (hybrid/).
#include <cstdint>
#include <optional>
#include <string>

namespace softsim::fem {

enum class ElementKind : std::uint8_t {
  linear = 0,        // small-strain, constant stiffness (000 eqs. 4–12)
  tled = 1,          // Total Lagrangian neo-Hookean (000 eqs. 13–22)
  corotational = 2,  // linear stiffness in the element's rotated frame (polar decomposition)
  anp = 3,           // TLED with the volumetric term averaged at the nodes (Bonet & Burton 1998):
                     // no volumetric locking as ν → 0.5 (see nodal_pressure.hpp)
};
inline constexpr int kNumElementKinds = 4;

// "linear", "tled", "corotational", "anp" — also the integer legend of the "element_kind" output.
const char* kind_name(ElementKind kind);
std::optional<ElementKind> parse_kind(const std::string& name);

}  // namespace softsim::fem
