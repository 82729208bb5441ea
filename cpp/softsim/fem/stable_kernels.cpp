#include "softsim/fem/stable_kernels.hpp"

#include "softsim/fem/kernel_macros.hpp"

#if defined(SOFTSIM_HAVE_OPENMP)
#define SOFTSIM_STABLE_SIMD _Pragma("omp simd")
#else
#define SOFTSIM_STABLE_SIMD
#endif

namespace softsim::fem::kernels {

namespace {

// kAveraged (ANP): λ (J − 1) becomes the mean of the corners' nodal pressures.
template <bool kAveraged>
void stable_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu, double lambda,
                   const double* __restrict pressure) {
  SOFTSIM_STABLE_SIMD
  for (int k = begin; k < end; ++k) {
    SOFTSIM_LOAD_H(s, u, k)
    SOFTSIM_F_AND_COFACTOR
    const double Ic = f00 * f00 + f01 * f01 + f02 * f02 + f10 * f10 + f11 * f11 + f12 * f12 + f20 * f20 +
                      f21 * f21 + f22 * f22;
    const double p = kAveraged ? 0.25 * (pressure[a0] + pressure[a1] + pressure[a2] + pressure[a3])
                               : lambda * (J - 1.0);
    const double V = s.vol[k];
    const double cf = V * mu * (1.0 - 1.0 / (Ic + 1.0));
    const double cc = V * (p - 0.75 * mu);
    SOFTSIM_STORE_FORCES(s, k, cf * f00 + cc * c00, cf * f01 + cc * c01, cf * f02 + cc * c02,
                         cf * f10 + cc * c10, cf * f11 + cc * c11, cf * f12 + cc * c12,
                         cf * f20 + cc * c20, cf * f21 + cc * c21, cf * f22 + cc * c22)
  }
}

}  // namespace

void tled_stable_kernel(const SoaView s, const double* __restrict u, int begin, int end,
                        const material::StableNeoHookean& law) {
  stable_kernel<false>(s, u, begin, end, law.mu, law.lambda, nullptr);
}

void anp_stable_kernel(const SoaView s, const double* __restrict u, int begin, int end,
                       const material::StableNeoHookean& rest, const double* __restrict pressure) {
  stable_kernel<true>(s, u, begin, end, rest.mu, 0.0, pressure);
}

}  // namespace softsim::fem::kernels
