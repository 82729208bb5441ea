#pragma once
// The compressible (decoupled) Mooney–Rivlin law, a hyperelastic law of the interface in
// hyperelastic.hpp (CalculiX *HYPERELASTIC, MOONEY-RIVLIN; Bonet & Wood 2008 §6.6):
//
//   W = C10 (Ī₁ − 3) + C01 (Ī₂ − 3) + K/2 (J − 1)²,
//   Ī₁ = J^(−2/3) I₁,  Ī₂ = J^(−4/3) I₂,  I₂ = ½ (I₁² − tr C²),  C = Fᵀ F,
//   S = 2 ∂W/∂C = 2 C10 J^(−2/3) (I − I₁/3 C⁻¹) + 2 C01 J^(−4/3) (I₁ I − C − 2/3 I₂ C⁻¹)
//       + K J (J − 1) C⁻¹,
//   P = F S = 2 C10 a (F − I₁/3 F⁻ᵀ) + 2 C01 a² (I₁ F − F C − 2/3 I₂ F⁻ᵀ) + K J (J − 1) F⁻ᵀ,
//   a = J^(−2/3).
//
// With C01 = 0 it is the decoupled neo-Hookean form (neo_hookean.hpp) with μ = 2 C10. At small
// strain it is linear elasticity with shear modulus μ = 2 (C10 + C01) and bulk modulus K.
#include <cmath>
#include <string>

#include <Eigen/Core>
#include <Eigen/LU>

#include "softsim/material/elastic.hpp"

namespace softsim::material {

struct MooneyRivlin {
  double c10 = 0;   // Pa
  double c01 = 0;   // Pa
  double bulk = 0;  // K (Pa)
};

// "mooney_rivlin".
std::string law_name(const MooneyRivlin& law);
// Throws InputError unless C10 + C01 > 0 and K > 0 (finite): a positive small-strain shear and
// bulk modulus.
void validate_moduli(const MooneyRivlin& law);
// The small-strain constants it linearises to (μ = 2 (C10 + C01), K), as (E, ν) with `density`:
// what the linear and corotational elements, the stable step and the wave speed use.
ElasticParameters small_strain_parameters(const MooneyRivlin& law, double density);

double strain_energy_density(const MooneyRivlin& law, const Eigen::Matrix3d& F);
Eigen::Matrix3d second_piola(const MooneyRivlin& law, const Eigen::Matrix3d& C);

// P = ∂W/∂F, inline: the TLED and ANP kernels evaluate it per element with the law as a
// template parameter (fem/law_kernels.hpp).
inline Eigen::Matrix3d first_piola(const MooneyRivlin& law, const Eigen::Matrix3d& F) {
  const double J = F.determinant();
  const Eigen::Matrix3d FinvT = F.inverse().transpose();
  const Eigen::Matrix3d C = F.transpose() * F;
  const double I1 = C.trace();
  const double I2 = 0.5 * (I1 * I1 - C.squaredNorm());  // tr C² = C:C (C symmetric)
  const double x = 1.0 / std::cbrt(J);  // cheaper than pow(J, -2/3) in the kernel's loop
  const double a = x * x;
  return 2.0 * law.c10 * a * (F - (I1 / 3.0) * FinvT) +
         2.0 * law.c01 * a * a * (I1 * F - F * C - (2.0 / 3.0) * I2 * FinvT) + law.bulk * J * (J - 1.0) * FinvT;
}

// dP(F)[dF]: what it needs of F alone, once for the 12 columns of an element tangent.
struct MooneyRivlinLinearisation {
  Eigen::Matrix3d F;
};
MooneyRivlinLinearisation linearise(const MooneyRivlin& law, const Eigen::Matrix3d& F);
Eigen::Matrix3d first_piola_increment(const MooneyRivlin& law, const MooneyRivlinLinearisation& at,
                                      const Eigen::Matrix3d& dF);

// The split W = W_iso(F) + U(J), U = κ/2 (J − 1)² with κ = K (for the average-nodal-pressure
// element): `isochoric_part` is the law with K = 0.
double volumetric_modulus(const MooneyRivlin& law);
MooneyRivlin isochoric_part(const MooneyRivlin& law);

}  // namespace softsim::material
