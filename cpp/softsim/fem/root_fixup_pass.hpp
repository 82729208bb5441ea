#pragma once
// The element loop shared by the kernels that need J^(−1/3) (law kernels of the decoupled kind):
// a vectorised pass with the Newton root (cube_root.hpp) over the range, then the elements whose
// J lies outside the range where that root is exact are recomputed with the library root, as
// the decoupled neo-Hookean kernel does (element_kernels.cpp). The choice depends on the element
// alone, so results do not depend on the split into threads. Private to the kernel sources.
#include <algorithm>
#include <cmath>

#include "softsim/fem/cube_root.hpp"

#if defined(SOFTSIM_HAVE_OPENMP)
#define SOFTSIM_FIXUP_SIMD_MINMAX _Pragma("omp simd reduction(min : jmin) reduction(max : jmax)")
#else
#define SOFTSIM_FIXUP_SIMD_MINMAX
#endif

namespace softsim::fem::kernels {

// Body: `template <bool kExactRoot> double element(int k) const` computes and stores element k's
// forces and returns its J. `scratch` (one per slot) keeps J between the two passes.
template <class Body>
void root_fixup_pass(const Body& body, int begin, int end, double* __restrict scratch, double& min_j) {
  double jmin = 1e300, jmax = -1e300;
  SOFTSIM_FIXUP_SIMD_MINMAX
  for (int k = begin; k < end; ++k) {
    const double J = body.template element<false>(k);
    scratch[k] = J;
    jmin = std::min(jmin, J);
    jmax = std::max(jmax, J);
  }
  if (jmin < kInvCbrtMinJ || jmax > kInvCbrtMaxJ)
    for (int k = begin; k < end; ++k) {
      const double J = scratch[k];
      if (J > 0 && (J < kInvCbrtMinJ || J > kInvCbrtMaxJ)) body.template element<true>(k);
    }
  min_j = std::min(min_j, jmin);
}

// J^(−1/3) by the Newton root or the library's (see above).
template <bool kExactRoot>
inline double inv_cbrt(double J) {
  if constexpr (kExactRoot) return 1.0 / std::cbrt(J);
  else return inv_cbrt_newton(J);
}

}  // namespace softsim::fem::kernels
