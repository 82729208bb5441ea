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

// The step from t_n to t_{n+1} = t_n + Δt₊ when the previous one was Δt₋ = t_n − t_{n−1}: the
// velocity form of 000 eq. 33 with a variable step,
//   M (v_{n+½} − v_{n−½}) / Δt_n + D (v_{n−½} + v_{n+½}) / 2 = R − F,  Δt_n = (Δt₋ + Δt₊) / 2,
//   v_{n−½} = (u_n − u_{n−1}) / Δt₋,  u_{n+1} = u_n + Δt₊ v_{n+½},
// in the same three-level form u_{n+1} = A (R − F) + B u_n − C u_{n−1}:
//   A = 2 Δt₊ Δt_n / (2M + D Δt_n),  C = (Δt₊/Δt₋) (2M − D Δt_n) / (2M + D Δt_n),  B = 1 + C.
// With Δt₋ = Δt₊ it is the constant-step update above (which is used then, so that a run whose
// step never changes is bit for bit the constant-step one).
inline CentralDifference central_difference(double mass, double alpha, double dt_before, double dt_after) {
  if (dt_before == dt_after) return central_difference(mass, alpha, dt_after);
  if (!(mass > 0)) return {};
  const double D = alpha * mass;
  const double dt_mid = 0.5 * (dt_before + dt_after);
  const double den = 2.0 * mass + D * dt_mid;
  const double C = dt_after / dt_before * (2.0 * mass - D * dt_mid) / den;
  return {2.0 * dt_after * dt_mid / den, 1.0 + C, C};
}

}  // namespace softsim::dynamics
