#pragma once
// The vectorised TLED and ANP kernels of the Ogden law (material/ogden.hpp). The law's own
// first_piola, the reference they are tested against, takes C's eigen-decomposition from
// Eigen's iterative solver; here the principal values come in closed form, without a loop that
// depends on the data and without a library call, so the element loop vectorises:
//
//  1. q = tr C / 3, B = C − q I, p = |B|/√6, r = det(B/p)/2 ∈ [−1, 1]: the eigenvalues are
//     q + p β with β³ − 3β = 2r. The root farthest from the other two (β ≥ √3 for r ≥ 0, its
//     mirror for r < 0) is found by two Newton steps from a quartic fit of it in |r|,
//     quadratic there (f' ≥ 6); being well separated it is accurate to round-off, unlike the two others, which
//     the trigonometric formula gives only to √eps when they nearly coincide.
//  2. Its eigenvector N: the largest cross product of two rows of C − c_s I, normalised.
//  3. The other two in N's orthogonal plane without a basis of it: E = C − m I − (c_s − m) N Nᵀ
//     with m = (tr C − c_s)/2 is the plane part of C less its mean, so c_± = m ± h with
//     h = |E|/√2, accurate to round-off however close (Weyl).
//  4. S_iso = Σ s_i N_i ⊗ N_i = s_s N Nᵀ + s̄ (I − N Nᵀ) + g E with s̄ = (s₊ + s₋)/2 and
//     g = (s₊ − s₋)/(2h), the divided difference; its cancellation error eps/h meets E of size h,
//     so S stays accurate at repeated and nearly repeated stretches. Degenerate cases: h = 0
//     gives g = 0 (E = 0 then), and C = q I (p = 0: no row to cross, any N serves) takes N = e₁.
//  5. λ̄_i^α = exp(α/2 ln(J^(−2/3) c_i)) by a vectorisable log and exp (vector_pow.hpp), the
//     logarithms once for all terms.
// P = F S_iso + p cof F with p = K (J − 1) (TLED) or the mean of the corners' nodal pressures
// (ANP). An inverted element (J ≤ 0) gets zero forces.
#include "softsim/fem/element_kernels.hpp"
#include "softsim/material/ogden.hpp"

namespace softsim::fem::kernels {

// `pressure` null: TLED; else ANP with the corners' nodal pressures (index 3a) and `law` the
// isochoric part. `scratch` one double per slot.
void ogden_forces(const material::Ogden& law, const SoaView s, const double* __restrict u, int begin, int end,
                  const double* __restrict pressure, double* __restrict scratch, double& min_j);

// Steps 1–3 above for one symmetric C (c00 c11 c22 c01 c12 c02): the closed form's principal
// values and c_s's eigenvector, for the tests.
struct PrincipalValues {
  double c[3];  // c_s, c₊, c₋
  double n[3];  // N of c_s
};
PrincipalValues principal_values(const double C[6]);

}  // namespace softsim::fem::kernels
