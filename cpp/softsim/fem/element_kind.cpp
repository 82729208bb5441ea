#include "softsim/fem/element_kind.hpp"

namespace softsim::fem {

const char* kind_name(ElementKind kind) {
  switch (kind) {
    case ElementKind::linear: return "linear";
    case ElementKind::tled: return "tled";
    case ElementKind::corotational: return "corotational";
    case ElementKind::anp: return "anp";
  }
  return "unknown";
}

std::optional<ElementKind> parse_kind(const std::string& name) {
  for (int k = 0; k < kNumElementKinds; ++k)
    if (name == kind_name(static_cast<ElementKind>(k))) return static_cast<ElementKind>(k);
  return std::nullopt;
}

}  // namespace softsim::fem
