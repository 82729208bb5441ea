#include "softsim/meshless/lee_radok.hpp"

#include <cmath>
#include <stdexcept>

namespace softsim::meshless {

IndentationModulus lee_radok_modulus(double force, double depth, double probe_radius, double poisson_ratio) {
  if (!(force > 0) || !(depth > 0) || !(probe_radius > 0) || !(poisson_ratio > -1 && poisson_ratio < 0.5))
    throw std::invalid_argument("lee_radok_modulus: need F, delta, R > 0 and -1 < nu < 0.5");
  IndentationModulus m;
  m.shear_modulus = 3.0 * force / (16.0 * depth * std::sqrt(probe_radius * depth));  // 002 eq. 47
  m.youngs_modulus = 2.0 * m.shear_modulus * (1.0 + poisson_ratio);                // 002 eq. 48
  return m;
}

}  // namespace softsim::meshless
