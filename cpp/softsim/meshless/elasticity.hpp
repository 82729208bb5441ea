#pragma once
// Isotropic linear elasticity as used by the global weak form (002 eqs. 4–7): the Lamé
// parameters and the stiffness block B_iᵀ D B_j of two nodes in closed form.

namespace softsim::meshless {

struct LameParameters {
  double lambda = 0;
  double mu = 0;
};
// Throws std::invalid_argument outside E > 0, -1 < ν < 0.5.
LameParameters lame_from_young(double youngs_modulus, double poisson_ratio);

// The 3 × 3 block w B_iᵀ D B_j of 002 eq. 19 in closed form for isotropic D:
//   K_ij[a][b] = w (λ ∂_a φ_i ∂_b φ_j + μ ∂_b φ_i ∂_a φ_j + μ δ_ab ∇φ_i·∇φ_j).
// Adds it to `block` (row-major 3 × 3).
inline void add_stiffness_block(const double* gi, const double* gj, double w, const LameParameters& m,
                                double* block) {
  const double dot = gi[0] * gj[0] + gi[1] * gj[1] + gi[2] * gj[2];
  const double lw = w * m.lambda, mw = w * m.mu;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) block[3 * a + b] += lw * gi[a] * gj[b] + mw * gi[b] * gj[a];
  block[0] += mw * dot;
  block[4] += mw * dot;
  block[8] += mw * dot;
}

}  // namespace softsim::meshless
