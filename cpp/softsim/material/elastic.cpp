#include "softsim/material/elastic.hpp"

#include <cmath>
#include <string>

#include "softsim/io/errors.hpp"

namespace softsim::material {

void validate(const ElasticParameters& p) {
  if (!(p.youngs_modulus > 0) || !std::isfinite(p.youngs_modulus))
    throw InputError("material: Young's modulus must be positive, got " + std::to_string(p.youngs_modulus));
  if (!(p.poisson_ratio > -1.0 && p.poisson_ratio < 0.5))
    throw InputError("material: Poisson's ratio must lie in (-1, 0.5), got " + std::to_string(p.poisson_ratio));
  if (!(p.density > 0) || !std::isfinite(p.density))
    throw InputError("material: density must be positive, got " + std::to_string(p.density));
}

LameParameters lame_parameters(const ElasticParameters& p) {
  const double E = p.youngs_modulus, nu = p.poisson_ratio;
  return {E / (2.0 * (1.0 + nu)), E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))};
}

double bulk_modulus(const ElasticParameters& p) {
  return p.youngs_modulus / (3.0 * (1.0 - 2.0 * p.poisson_ratio));
}

ElasticParameters from_lame(double mu, double lambda, double density) {
  ElasticParameters p;
  p.youngs_modulus = mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
  p.poisson_ratio = lambda / (2.0 * (lambda + mu));
  p.density = density;
  return p;
}

ElasticParameters from_shear_bulk(double mu, double bulk, double density) {
  return from_lame(mu, bulk - 2.0 * mu / 3.0, density);
}

double dilatational_wave_speed(const ElasticParameters& p) {
  const double E = p.youngs_modulus, nu = p.poisson_ratio;
  return std::sqrt(E * (1.0 - nu) / (p.density * (1.0 + nu) * (1.0 - 2.0 * nu)));  // 000 eq. 35
}

}  // namespace softsim::material
