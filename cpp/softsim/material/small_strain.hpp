#pragma once
// Small-strain isotropic elasticity and its corotated extension, both written through the
// deformation gradient F = I + H (H = ∇u) so that every element kind speaks the same
// language (P(F), W(F), dP(F)[dF]).
//
//   linear (000 eqs. 9–10):  ε = sym(F − I), P = σ = 2μ ε + λ tr(ε) I, W = μ ε:ε + λ/2 tr²(ε).
//     Not invariant under rotation: a rigid rotation produces stress.
//   corotated: F = R S (polar decomposition), the linear law applied to the stretch S − I in
//     the element's rotated frame: P = R σ(S − I) = 2μ (F − R) + λ tr(S − I) R,
//     W = μ ‖S − I‖² + λ/2 tr²(S − I). P is the exact gradient of W (McAdams et al. 2011), so
//     the element force V₀ P ∇N equals R Kₑ (Rᵀ x − X) with the linear stiffness block Kₑ.
#include <Eigen/Core>

#include "softsim/material/elastic.hpp"

namespace softsim::material {

Eigen::Matrix3d linear_stress(const LameParameters& l, const Eigen::Matrix3d& F);
double linear_energy_density(const LameParameters& l, const Eigen::Matrix3d& F);
Eigen::Matrix3d linear_stress_increment(const LameParameters& l, const Eigen::Matrix3d& dF);

Eigen::Matrix3d corotated_first_piola(const LameParameters& l, const Eigen::Matrix3d& F);
double corotated_energy_density(const LameParameters& l, const Eigen::Matrix3d& F);
// dP including the rotation's variation dR = R W, W skew with axial vector
// w = (tr(S) I − S)⁻¹ axial(Rᵀ dF − dFᵀ R).
Eigen::Matrix3d corotated_first_piola_increment(const LameParameters& l, const Eigen::Matrix3d& F,
                                                const Eigen::Matrix3d& dF);

// What the corotated dP(F)[·] needs of F alone, for many increments at one F (the 12 columns of
// an element tangent): the rotation R of F = R S (the polar decomposition) and (tr(S) I − S)⁻¹.
struct CorotatedLinearisation {
  Eigen::Matrix3d R;
  Eigen::Matrix3d Ginv;  // (tr(S) I − S)⁻¹
  double trE = 0;        // tr(S − I)
};
CorotatedLinearisation corotated_linearise(const Eigen::Matrix3d& F);
// The same dP as corotated_first_piola_increment(l, F, dF), from the set-up at F.
Eigen::Matrix3d corotated_first_piola_increment(const LameParameters& l, const CorotatedLinearisation& at,
                                                const Eigen::Matrix3d& dF);

}  // namespace softsim::material
