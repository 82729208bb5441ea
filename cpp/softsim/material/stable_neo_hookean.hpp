#pragma once
// The stable neo-Hookean law of Smith, de Goes and Kim (2018, "Stable Neo-Hookean Flesh
// Simulation", ACM TOG 37(2) 12), a hyperelastic law of the interface in hyperelastic.hpp that
// stays defined, smooth and restoring through flattening and inversion (J ≤ 0):
//
//   W = μ/2 (I_C − 3) + λ/2 (J − α)² − μ/2 ln(I_C + 1),   α = 1 + 3μ/(4λ),
//   I_C = tr(FᵀF),  J = det F.
//
// No ln J and no J^(−2/3): nothing is singular at J = 0, so an inverted element has a finite
// energy and a stress that pushes it back (the λ term's gradient λ (J − α) cof F points towards
// larger J whenever J < α). The −μ/2 ln(I_C + 1) term keeps the energy from having its minimum
// on a collapsed element (Smith et al. §3.3, "rest stability"), and α is what makes F = I
// stress-free with it: ∂W/∂F at I is μ I − μ/4 I + λ (1 − α) I = 0.
//
// We store it in the equivalent form (equal up to the constant that makes W(I) = 0)
//
//   W = μ/2 (I_C − 3) − μ/2 ln((I_C + 1)/4) − 3μ/4 (J − 1) + λ/2 (J − 1)²,
//   P = μ (1 − 1/(I_C + 1)) F + (λ (J − 1) − 3μ/4) cof F,   cof F = ∂J/∂F = J F⁻ᵀ,
//
// which has λ/2 (J − 1)² as its volumetric term U(J) (the split the ANP element needs) and no
// division by λ. Linearised at F = I it is linear elasticity with shear modulus 3μ/4 and Lamé
// λ − 5μ/8, so (E, ν) with Lamé constants (μ_L, λ_L) map to Smith et al.'s reparametrisation
// (their §3.4)
//
//   μ = 4/3 μ_L,   λ = λ_L + 5/6 μ_L,
//
// and small strains match the linear, corotational and other hyperelastic elements.
#include <cmath>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "softsim/material/elastic.hpp"
#include "softsim/material/inversion_robust.hpp"

namespace softsim::material {

struct StableNeoHookean {
  double mu = 0;      // Smith et al.'s μ (4/3 of the small-strain shear modulus)
  double lambda = 0;  // Smith et al.'s λ (λ_L + 5/6 μ_L)

  // The reparametrisation above from the small-strain (E, ν).
  static StableNeoHookean from(const ElasticParameters& p);
};

// Inverted elements are states, not failures (inversion_robust.hpp).
template <>
inline constexpr bool kInversionRobust<StableNeoHookean> = true;

// "stable_neo_hookean".
std::string law_name(const StableNeoHookean& law);
// The small-strain (E, ν) it linearises to (shear 3μ/4, Lamé λ − 5μ/8), with `density`.
ElasticParameters small_strain_parameters(const StableNeoHookean& law, double density);

// cof F = ∂ det F / ∂F: column J is the cross product of the other two columns (in cyclic order).
inline Eigen::Matrix3d cofactor(const Eigen::Matrix3d& F) {
  Eigen::Matrix3d c;
  c.col(0) = F.col(1).cross(F.col(2));
  c.col(1) = F.col(2).cross(F.col(0));
  c.col(2) = F.col(0).cross(F.col(1));
  return c;
}

// Defined for every F, inverted ones included.
double strain_energy_density(const StableNeoHookean& law, const Eigen::Matrix3d& F);
// S = F⁻¹ P = μ (1 − 1/(I_C + 1)) I + (λ (J − 1) − 3μ/4) J C⁻¹, with J = sqrt(det C): C does not
// know the orientation, so this is S of the non-inverted F with that C (the stress outputs of
// an inverted element use P(F) instead).
Eigen::Matrix3d second_piola(const StableNeoHookean& law, const Eigen::Matrix3d& C);

// P = ∂W/∂F, inline for the TLED and ANP kernels (fem/law_kernels.hpp).
inline Eigen::Matrix3d first_piola(const StableNeoHookean& law, const Eigen::Matrix3d& F) {
  const Eigen::Matrix3d cof = cofactor(F);
  const double J = F.col(0).dot(cof.col(0));
  const double Ic = F.squaredNorm();
  return law.mu * (1.0 - 1.0 / (Ic + 1.0)) * F + (law.lambda * (J - 1.0) - 0.75 * law.mu) * cof;
}

struct StableNeoHookeanLinearisation {
  Eigen::Matrix3d F;
  Eigen::Matrix3d cof;
  double J = 0, Ic = 0;
};
StableNeoHookeanLinearisation linearise(const StableNeoHookean& law, const Eigen::Matrix3d& F);
// dP[dF] = μ (1 − 1/(I_C+1)) dF + 2μ (F:dF)/(I_C+1)² F + λ (cof F:dF) cof F
//          + (λ (J − 1) − 3μ/4) dcof[dF],  column J of dcof: df_{J+1} × f_{J+2} + f_{J+1} × df_{J+2}.
Eigen::Matrix3d first_piola_increment(const StableNeoHookean& law, const StableNeoHookeanLinearisation& at,
                                      const Eigen::Matrix3d& dF);

// W = W_rest(F) + U(J) with U = λ/2 (J − 1)²: κ = λ, and `isochoric_part` is the law with λ = 0
// (μ/2 (I_C − 3) − μ/2 ln((I_C + 1)/4) − 3μ/4 (J − 1): not isochoric in the strict sense, but
// all of W except U, which is what the ANP element's split needs).
double volumetric_modulus(const StableNeoHookean& law);
StableNeoHookean isochoric_part(const StableNeoHookean& law);

}  // namespace softsim::material
