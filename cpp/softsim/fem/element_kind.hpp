#pragma once
// The element formulations an element can be given (000 §2.2.2 plus the corotational and
// average-nodal-pressure variants): chosen per element by the partition (hybrid/).
//
// kElementKinds is the one table of them: the integer code (the enum value and the index in
// the table), the name configs and artifacts use, a one-line description and whether the kind
// is small-strain (linear stiffness, the cheap kinds a partition puts away from the operating
// point). The dhd_result artifact's element_kind_legend, its element_counts, dhd_sim's --bench
// columns and --help, and the Python bindings are all generated from it.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace softsim::fem {

enum class ElementKind : std::uint8_t {
  linear = 0,        // small-strain, constant stiffness (000 eqs. 4–12)
  tled = 1,          // Total Lagrangian neo-Hookean (000 eqs. 13–22)
  corotational = 2,  // linear stiffness in the element's rotated frame (polar decomposition)
  anp = 3,           // TLED with the volumetric term averaged at the nodes (Bonet & Burton 1998):
                     // one volume constraint per node (see nodal_pressure.hpp)
  smoothed = 4,      // selective smoothed FEM: isochoric part on edge-smoothed gradients (ES-FEM),
                     // volumetric part at the nodes as ANP (see edge_smoothing.hpp)
};

struct ElementKindInfo {
  ElementKind kind;
  const char* name;
  const char* description;
  bool small_strain;
};

inline constexpr std::array<ElementKindInfo, 5> kElementKinds{{
    {ElementKind::linear, "linear", "small-strain linear elastic, constant stiffness (000 eqs. 4-12)", true},
    {ElementKind::tled, "tled", "Total Lagrangian explicit neo-Hookean (000 eqs. 13-22)", false},
    {ElementKind::corotational, "corotational",
     "linear stiffness in the element's rotated frame (polar decomposition F = R S)", true},
    {ElementKind::anp, "anp",
     "TLED with the volumetric pressure averaged at the nodes (Bonet & Burton 1998)", false},
    {ElementKind::smoothed, "smoothed",
     "selective smoothed FEM: isochoric part on edge-smoothed gradients, volumetric part at the nodes", false},
}};
inline constexpr int kNumElementKinds = static_cast<int>(kElementKinds.size());

// Whether the kind's volumetric term U(J) lives at the nodes (nodal_pressure.hpp): its elements
// share one nodal volume ratio J_a.
inline constexpr bool volumetric_at_nodes(ElementKind kind) {
  return kind == ElementKind::anp || kind == ElementKind::smoothed;
}

// Every entry's kind is its index: code k is kElementKinds[k].
constexpr bool element_kind_table_is_indexed() {
  for (int k = 0; k < kNumElementKinds; ++k)
    if (static_cast<int>(kElementKinds[k].kind) != k) return false;
  return true;
}
static_assert(element_kind_table_is_indexed(), "kElementKinds must list the kinds in the order of their codes");

inline constexpr const ElementKindInfo& kind_info(ElementKind kind) { return kElementKinds[static_cast<int>(kind)]; }

// "linear", "tled", "corotational", "anp", "smoothed" — also the integer legend of the "element_kind" output.
const char* kind_name(ElementKind kind);
std::optional<ElementKind> parse_kind(const std::string& name);

// The names of every kind in code order; with `small_strain` given, of the kinds whose
// small_strain flag equals it.
std::vector<std::string> kind_names();
std::vector<std::string> kind_names(bool small_strain);

// "0 linear, 1 tled, 2 corotational, 3 anp, 4 smoothed": the legend in words, for help texts and docstrings.
std::string kind_legend_text();

}  // namespace softsim::fem
