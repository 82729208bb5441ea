#pragma once
// The explicit TLED and ANP kernels of the stable neo-Hookean law (material/stable_neo_hookean.hpp),
// written on the shared kernel macros like the neo-Hookean ones so the element loop vectorises:
// the generic kernel (law_kernels.cpp) builds an Eigen matrix per element and calls the law,
// which takes several times as long. The law is defined for every J, so there is no branch on
// J and no min_j: its inverted elements are not failures (material/inversion_robust.hpp).
#include "softsim/fem/element_kernels.hpp"
#include "softsim/material/stable_neo_hookean.hpp"

namespace softsim::fem::kernels {

// ⁰V P ∇N with P = μ (1 − 1/(I_C + 1)) F + (λ (J − 1) − 3μ/4) cof F.
void tled_stable_kernel(const SoaView s, const double* __restrict u, int begin, int end,
                        const material::StableNeoHookean& law);

// ANP with the law's part without U(J) (`rest`: λ = 0) and p̄ the mean of the corners' nodal
// pressures (index 3a): P = μ (1 − 1/(I_C + 1)) F + (p̄ − 3μ/4) cof F.
void anp_stable_kernel(const SoaView s, const double* __restrict u, int begin, int end,
                       const material::StableNeoHookean& rest, const double* __restrict pressure);

}  // namespace softsim::fem::kernels
