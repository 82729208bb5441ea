#include "softsim/multirate/bar_model.hpp"

#include <cmath>

#include "softsim/io/errors.hpp"

namespace softsim::multirate {

LinearModel make_bar(const BarSpec& spec) {
  if (spec.nodes < 2) throw InputError("bar: at least 2 nodes are needed");
  for (double v : {spec.length, spec.area, spec.youngs_modulus, spec.density})
    if (!(v > 0) || !std::isfinite(v)) throw InputError("bar: length, area, E and density must be positive");
  LinearModel model;
  model.dofs_per_node = 1;
  const int elements = spec.nodes - 1;
  const double h = bar_element_length(spec);
  const double k = bar_element_stiffness(spec);
  const double element_mass = bar_element_mass(spec);  // lumped: half to each end
  model.positions.resize(spec.nodes);
  model.nodal_mass.assign(spec.nodes, 0.0);
  for (int n = 0; n < spec.nodes; ++n) model.positions[n] = Eigen::Vector3d(n * h, 0.0, 0.0);
  for (int e = 0; e < elements; ++e) {
    LinearElement el;
    el.nodes = {e, e + 1};
    el.stiffness.resize(2, 2);
    el.stiffness << k, -k, -k, k;
    model.elements.push_back(std::move(el));
    model.nodal_mass[e] += 0.5 * element_mass;
    model.nodal_mass[e + 1] += 0.5 * element_mass;
  }
  model.fixed_nodes = {0};
  return model;
}

}  // namespace softsim::multirate
