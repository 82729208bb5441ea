#include "softsim/meshless/studies.hpp"

#include <cmath>

#include "softsim/io/errors.hpp"

namespace softsim::meshless {

std::string stability_parameter_name(StabilityParameter p) {
  switch (p) {
    case StabilityParameter::q: return "q";
    case StabilityParameter::alpha_c: return "alpha_c";
    case StabilityParameter::d_c_spacing_factor: return "d_c_spacing_factor";
    case StabilityParameter::support_spacing_factor: return "support_spacing_factor";
    case StabilityParameter::nearest_count: return "nearest_count";
  }
  return "?";
}

StabilityPoint stability_point(const PlateScene& scene, RpimSettings settings, StabilityParameter parameter,
                               double value) {
  StabilityPoint p;
  p.parameter = parameter;
  p.value = value;
  switch (parameter) {
    case StabilityParameter::q: settings.q = value; break;
    case StabilityParameter::alpha_c: settings.alpha_c = value; break;
    case StabilityParameter::d_c_spacing_factor: settings.d_c = {LengthSpec::Kind::spacing_factor, value}; break;
    case StabilityParameter::support_spacing_factor:
      settings.support = SupportRule::Kind::radius;
      settings.support_radius = {LengthSpec::Kind::spacing_factor, value};
      break;
    case StabilityParameter::nearest_count:
      settings.support = SupportRule::Kind::nearest;
      settings.support_count = static_cast<int>(std::lround(value));
      break;
  }
  try {
    const PlateRun run = run_plate(scene, settings, {}, true);
    for (int a = 0; a < 3; ++a) p.compliance[a] = run.unit_solutions(3 * run.loaded_node_index + a, a);
    p.conditioning = run.conditioning;
    p.rbf = run.rbf;
    p.support = run.support;
    p.ok = true;
  } catch (const NumericalError& e) {
    p.ok = false;
    p.message = e.what();
  }
  return p;
}

std::vector<ConvergencePoint> convergence_study(const BlockStudy& block, const RpimSettings& settings,
                                                const std::vector<int>& nodes_per_edge) {
  std::vector<ConvergencePoint> out;
  for (int n : nodes_per_edge) {
    BlockStudy b = block;
    b.nodes_per_edge = n;
    b.cells_per_edge = n - 1;
    out.push_back({n, run_block_study(b, settings)});
  }
  return out;
}

double observed_rate(const std::vector<double>& spacing, const std::vector<double>& error) {
  const std::size_t n = spacing.size();
  if (n < 2 || error.size() != n) return 0;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += std::log(spacing[i]);
    my += std::log(error[i]);
  }
  mx /= n;
  my /= n;
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = std::log(spacing[i]) - mx;
    sxy += dx * (std::log(error[i]) - my);
    sxx += dx * dx;
  }
  return sxx > 0 ? sxy / sxx : 0;
}

}  // namespace softsim::meshless
