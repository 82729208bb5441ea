#include "softsim/fem/element_kind.hpp"

namespace softsim::fem {

const char* kind_name(ElementKind kind) {
  const int k = static_cast<int>(kind);
  return k < kNumElementKinds ? kElementKinds[k].name : "unknown";
}

std::optional<ElementKind> parse_kind(const std::string& name) {
  for (const ElementKindInfo& info : kElementKinds)
    if (name == info.name) return info.kind;
  return std::nullopt;
}

std::vector<std::string> kind_names() {
  std::vector<std::string> out;
  for (const ElementKindInfo& info : kElementKinds) out.emplace_back(info.name);
  return out;
}

std::vector<std::string> kind_names(bool small_strain) {
  std::vector<std::string> out;
  for (const ElementKindInfo& info : kElementKinds)
    if (info.small_strain == small_strain) out.emplace_back(info.name);
  return out;
}

std::string kind_legend_text() {
  std::string out;
  for (int k = 0; k < kNumElementKinds; ++k)
    out += (k ? ", " : "") + std::to_string(k) + " " + kElementKinds[k].name;
  return out;
}

}  // namespace softsim::fem
