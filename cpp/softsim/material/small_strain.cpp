#include "softsim/material/small_strain.hpp"

#include <Eigen/Dense>

#include "softsim/material/polar_decomposition.hpp"

namespace softsim::material {

namespace {
const Eigen::Matrix3d kI = Eigen::Matrix3d::Identity();

Eigen::Matrix3d sigma(const LameParameters& l, const Eigen::Matrix3d& eps) {
  return 2.0 * l.mu * eps + l.lambda * eps.trace() * kI;
}
}  // namespace

Eigen::Matrix3d linear_stress(const LameParameters& l, const Eigen::Matrix3d& F) {
  const Eigen::Matrix3d H = F - kI;
  return sigma(l, 0.5 * (H + H.transpose()));  // 000 eq. 10
}

double linear_energy_density(const LameParameters& l, const Eigen::Matrix3d& F) {
  const Eigen::Matrix3d H = F - kI;
  const Eigen::Matrix3d eps = 0.5 * (H + H.transpose());
  return l.mu * eps.squaredNorm() + 0.5 * l.lambda * eps.trace() * eps.trace();
}

Eigen::Matrix3d linear_stress_increment(const LameParameters& l, const Eigen::Matrix3d& dF) {
  return sigma(l, 0.5 * (dF + dF.transpose()));
}

Eigen::Matrix3d corotated_first_piola(const LameParameters& l, const Eigen::Matrix3d& F) {
  const Polar p = polar_decomposition(F);
  return p.R * sigma(l, p.S - kI);
}

double corotated_energy_density(const LameParameters& l, const Eigen::Matrix3d& F) {
  const Polar p = polar_decomposition(F);
  const Eigen::Matrix3d E = p.S - kI;
  return l.mu * E.squaredNorm() + 0.5 * l.lambda * E.trace() * E.trace();
}

Eigen::Matrix3d corotated_first_piola_increment(const LameParameters& l, const Eigen::Matrix3d& F,
                                                const Eigen::Matrix3d& dF) {
  return corotated_first_piola_increment(l, corotated_linearise(F), dF);
}

CorotatedLinearisation corotated_linearise(const Eigen::Matrix3d& F) {
  const Polar p = polar_decomposition(F);
  CorotatedLinearisation at;
  at.R = p.R;
  const Eigen::Matrix3d G = p.S.trace() * kI - p.S;
  at.Ginv = G.inverse();
  at.trE = p.S.trace() - 3.0;
  return at;
}

Eigen::Matrix3d corotated_first_piola_increment(const LameParameters& l, const CorotatedLinearisation& at,
                                                const Eigen::Matrix3d& dF) {
  const Eigen::Matrix3d A = at.R.transpose() * dF;
  const Eigen::Matrix3d K = A - A.transpose();  // = W S + S W
  const Eigen::Vector3d k(K(2, 1), K(0, 2), K(1, 0));
  const Eigen::Vector3d w = at.Ginv * k;
  Eigen::Matrix3d W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  const Eigen::Matrix3d dR = at.R * W;
  // P = 2μ (F − R) + λ tr(S − I) R;  tr(dS) = tr(Rᵀ dF) because tr(W S) = 0.
  return 2.0 * l.mu * (dF - dR) + l.lambda * (A.trace() * at.R + at.trE * dR);
}

}  // namespace softsim::material
