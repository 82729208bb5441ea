#include "softsim/material/mooney_rivlin.hpp"

#include "softsim/io/errors.hpp"
#include "softsim/material/isochoric_increment.hpp"

namespace softsim::material {

std::string law_name(const MooneyRivlin&) { return "mooney_rivlin"; }

void validate_moduli(const MooneyRivlin& law) {
  const double mu = 2.0 * (law.c10 + law.c01);
  if (!(mu > 0) || !std::isfinite(mu))
    throw InputError("material: Mooney-Rivlin C10 + C01 must be positive, got " + std::to_string(mu / 2.0));
  if (!(law.bulk > 0) || !std::isfinite(law.bulk))
    throw InputError("material: Mooney-Rivlin bulk modulus K must be positive, got " + std::to_string(law.bulk));
}

ElasticParameters small_strain_parameters(const MooneyRivlin& law, double density) {
  const double mu = 2.0 * (law.c10 + law.c01);
  return from_shear_bulk(mu, law.bulk, density);
}

double strain_energy_density(const MooneyRivlin& law, const Eigen::Matrix3d& F) {
  const double J = F.determinant();
  const Eigen::Matrix3d C = F.transpose() * F;
  const double I1 = C.trace();
  const double I2 = 0.5 * (I1 * I1 - C.squaredNorm());
  const double a = std::pow(J, -2.0 / 3.0);
  return law.c10 * (a * I1 - 3.0) + law.c01 * (a * a * I2 - 3.0) + 0.5 * law.bulk * (J - 1.0) * (J - 1.0);
}

Eigen::Matrix3d second_piola(const MooneyRivlin& law, const Eigen::Matrix3d& C) {
  const double J = std::sqrt(C.determinant());
  const Eigen::Matrix3d Cinv = C.inverse();
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const double I1 = C.trace();
  const double I2 = 0.5 * (I1 * I1 - C.squaredNorm());
  const double a = std::pow(J, -2.0 / 3.0);
  return 2.0 * law.c10 * a * (I - (I1 / 3.0) * Cinv) + 2.0 * law.c01 * a * a * (I1 * I - C - (2.0 / 3.0) * I2 * Cinv) +
         law.bulk * J * (J - 1.0) * Cinv;
}

MooneyRivlinLinearisation linearise(const MooneyRivlin&, const Eigen::Matrix3d& F) { return {F}; }

// The derivative of P (header) term by term, with dJ = J tr(F⁻¹dF), da = −2/3 a tr(F⁻¹dF),
// dF⁻ᵀ = −F⁻ᵀ dFᵀ F⁻ᵀ, dC = dFᵀF + FᵀdF, dI₁ = tr dC, dI₂ = I₁ dI₁ − C:dC.
Eigen::Matrix3d first_piola_increment(const MooneyRivlin& law, const MooneyRivlinLinearisation& at,
                                      const Eigen::Matrix3d& dF) {
  const Eigen::Matrix3d& F = at.F;
  const IsochoricIncrement k(F, dF);
  const double a = k.a, da = k.da;
  const Eigen::Matrix3d &FinvT = k.FinvT, &dFinvT = k.dFinvT;
  const Eigen::Matrix3d C = F.transpose() * F;
  const Eigen::Matrix3d dC = dF.transpose() * F + F.transpose() * dF;
  const double I1 = C.trace(), dI1 = dC.trace();
  const double I2 = 0.5 * (I1 * I1 - C.squaredNorm());
  const double dI2 = I1 * dI1 - (C.array() * dC.array()).sum();
  const Eigen::Matrix3d iso1 = da * (F - (I1 / 3.0) * FinvT) + a * (dF - (dI1 / 3.0) * FinvT - (I1 / 3.0) * dFinvT);
  const Eigen::Matrix3d iso2 = 2.0 * a * da * (I1 * F - F * C - (2.0 / 3.0) * I2 * FinvT) +
                               a * a *
                                   (dI1 * F + I1 * dF - dF * C - F * dC - (2.0 / 3.0) * dI2 * FinvT -
                                    (2.0 / 3.0) * I2 * dFinvT);
  return 2.0 * law.c10 * iso1 + 2.0 * law.c01 * iso2 + k.volumetric(law.bulk);
}

double volumetric_modulus(const MooneyRivlin& law) { return law.bulk; }

MooneyRivlin isochoric_part(const MooneyRivlin& law) {
  MooneyRivlin iso = law;
  iso.bulk = 0.0;
  return iso;
}

}  // namespace softsim::material
