#pragma once
// The kinematics the static tangents dP(F)[dF] of the decoupled laws share (mooney_rivlin.cpp,
// transversely_isotropic.cpp): with t = tr(F⁻¹dF), dJ = J t, the isochoric factor a = J^(−2/3)
// and da = −2/3 a t, dF⁻ᵀ = −F⁻ᵀ dFᵀ F⁻ᵀ, and the increment of the volumetric term
// K/2 (J − 1)², whose first Piola stress is K J (J − 1) F⁻ᵀ.
#include <cmath>

#include <Eigen/Core>
#include <Eigen/LU>

namespace softsim::material {

struct IsochoricIncrement {
  IsochoricIncrement(const Eigen::Matrix3d& F, const Eigen::Matrix3d& dF) {
    J = F.determinant();
    const Eigen::Matrix3d Finv = F.inverse();
    FinvT = Finv.transpose();
    t = (Finv * dF).trace();
    dJ = J * t;
    a = std::pow(J, -2.0 / 3.0);
    da = -2.0 / 3.0 * a * t;
    dFinvT = -FinvT * dF.transpose() * FinvT;
  }
  // d[K J (J − 1) F⁻ᵀ].
  Eigen::Matrix3d volumetric(double bulk) const {
    return bulk * ((2.0 * J - 1.0) * dJ * FinvT + J * (J - 1.0) * dFinvT);
  }
  double J, t, dJ, a, da;
  Eigen::Matrix3d FinvT, dFinvT;
};

}  // namespace softsim::material
