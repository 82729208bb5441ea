#include "softsim/meshless/elasticity.hpp"

#include <stdexcept>

namespace softsim::meshless {

LameParameters lame_from_young(double e, double nu) {
  if (!(e > 0) || !(nu > -1.0) || !(nu < 0.5))
    throw std::invalid_argument("lame_from_young: need E > 0 and -1 < nu < 0.5");
  return {e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))};
}

Eigen::Matrix<double, 6, 6> elasticity_matrix(double e, double nu) {
  const double f = e / ((1 + nu) * (1 - 2 * nu));
  const double d11 = f * (1 - nu), d12 = f * nu;  // 002 eq. 7
  Eigen::Matrix<double, 6, 6> d = Eigen::Matrix<double, 6, 6>::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) d(i, j) = i == j ? d11 : d12;
  for (int i = 3; i < 6; ++i) d(i, i) = 0.5 * (d11 - d12);
  return d;
}

Eigen::Matrix<double, 6, 3> strain_matrix(const Eigen::Vector3d& g) {
  Eigen::Matrix<double, 6, 3> b = Eigen::Matrix<double, 6, 3>::Zero();
  b(0, 0) = g.x();                    // εxx = ∂u/∂x
  b(1, 1) = g.y();                    // εyy = ∂v/∂y
  b(2, 2) = g.z();                    // εzz = ∂w/∂z
  b(3, 1) = g.z(); b(3, 2) = g.y();   // γyz = ∂v/∂z + ∂w/∂y
  b(4, 0) = g.z(); b(4, 2) = g.x();   // γxz = ∂u/∂z + ∂w/∂x
  b(5, 0) = g.y(); b(5, 1) = g.x();   // γxy = ∂u/∂y + ∂v/∂x
  return b;
}

}  // namespace softsim::meshless
