#include "softsim/meshless/elasticity.hpp"

#include <stdexcept>

namespace softsim::meshless {

LameParameters lame_from_young(double e, double nu) {
  if (!(e > 0) || !(nu > -1.0) || !(nu < 0.5))
    throw std::invalid_argument("lame_from_young: need E > 0 and -1 < nu < 0.5");
  return {e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))};
}

}  // namespace softsim::meshless
