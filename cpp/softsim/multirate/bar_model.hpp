#pragma once
// The one-dimensional model of 001 §6: a bar of N nodes along x, two-node linear elements
// (axial stiffness E A / h), lumped mass rho A h / 2 per element end. Node 0 (x = 0) is fixed;
// the probe touches the free end, node N - 1 (x = L).
#include "softsim/multirate/linear_model.hpp"

namespace softsim::multirate {

struct BarSpec {
  int nodes = 40;                  // N, including the fixed node
  double length = 0.04;            // L (m)
  double area = 1e-4;              // cross-section A (m^2)
  double youngs_modulus = 5e3;     // E (Pa)
  double density = 1000.0;         // rho (kg/m^3)
};

// Throws InputError for fewer than 2 nodes or a non-positive property.
LinearModel make_bar(const BarSpec& spec);

// The element length h = L / (N - 1).
inline double bar_element_length(const BarSpec& spec) { return spec.length / (spec.nodes - 1); }

// The axial element stiffness E A / h and the element mass rho A h (half to each end).
inline double bar_element_stiffness(const BarSpec& spec) {
  return spec.youngs_modulus * spec.area / bar_element_length(spec);
}
inline double bar_element_mass(const BarSpec& spec) { return spec.density * spec.area * bar_element_length(spec); }

// The contact node of the bar: its free end.
inline int bar_contact_node(const BarSpec& spec) { return spec.nodes - 1; }

}  // namespace softsim::multirate
