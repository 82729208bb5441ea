#include "softsim/fit/dataset.hpp"

#include <algorithm>
#include <cmath>

namespace softsim::fit {

std::vector<double> loaded_displacements(const Dataset& data, int component) {
  std::vector<double> out;
  out.reserve(data.cases.size());
  for (const auto& c : data.cases) out.push_back(c.displacement(data.loaded_node, component));
  return out;
}

std::vector<double> force_components(const Dataset& data, int direction) {
  std::vector<double> out;
  out.reserve(data.cases.size());
  for (const auto& c : data.cases) out.push_back(c.force[direction]);
  return out;
}

double off_axis_fraction(const Dataset& data, int direction) {
  double largest = 0.0, off = 0.0;
  for (const auto& c : data.cases) {
    largest = std::max(largest, c.force.norm());
    for (int a = 0; a < 3; ++a)
      if (a != direction) off = std::max(off, std::abs(c.force[a]));
  }
  return largest > 0.0 ? off / largest : 0.0;
}

}  // namespace softsim::fit
