#pragma once
// J^(−1/3) without a library call, so the decoupled neo-Hookean kernel stays vectorisable:
// a [1/1] Padé start (exact value and slope at J = 1) and six division-free Newton steps
// x ← x (4 − J x³)/3. Accurate to a few ulp for J in [1/8, 8] (tested); callers recompute
// elements outside that range with std::cbrt.
namespace softsim::fem {

inline constexpr double kInvCbrtMinJ = 0.125;
inline constexpr double kInvCbrtMaxJ = 8.0;

inline double inv_cbrt_newton(double J) {
  double x = (2.0 + J) / (1.0 + 2.0 * J);
  for (int i = 0; i < 6; ++i) x = x * (4.0 - J * (x * x * x)) * (1.0 / 3.0);
  return x;
}

}  // namespace softsim::fem
