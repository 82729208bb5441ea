#pragma once
// Central-difference update of one node with lumped mass M and damping D = αM (000 eqs. 29–33):
//   u(t+Δt) = A (R − F) + B u(t) − C u(t−Δt),
//   A = 2Δt² / (2M + DΔt),  B = 4M / (2M + DΔt),  C = (2M − DΔt) / (2M + DΔt)
// (000 eq. 32 divided through by Δt). A node without mass keeps its displacement (A = C = 0, B = 1).
namespace softsim::dynamics {

struct CentralDifference {
  double A = 0;
  double B = 1;
  double C = 0;
};

inline CentralDifference central_difference(double mass, double alpha, double dt) {
  if (!(mass > 0)) return {};
  const double D = alpha * mass;
  const double den = 2.0 * mass + D * dt;
  return {2.0 * dt * dt / den, 4.0 * mass / den, (2.0 * mass - D * dt) / den};  // 000 eq. 33
}

}  // namespace softsim::dynamics
