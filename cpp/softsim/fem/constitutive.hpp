#pragma once
// One material seen by every element kind: linear and corotational elements use the
// small-strain law with (μ, λ); TLED elements use the chosen neo-Hookean form with the same
// (E, ν); ANP elements its isochoric part only — their volumetric part U(J) lives at the nodes
// (nodal_pressure.hpp). Everything element-local is expressed as P(F), W(F) and dP(F)[dF].
#include <Eigen/Core>

#include "softsim/fem/element_kind.hpp"
#include "softsim/material/elastic.hpp"
#include "softsim/material/neo_hookean.hpp"

namespace softsim::fem {

struct Material {
  material::ElasticParameters elastic;
  material::LameParameters lame;
  material::NeoHookean neo_hookean;
  material::NeoHookean isochoric;  // neo_hookean without its volumetric term (ANP elements)
  double volumetric_modulus = 0;   // κ of U(J) = κ/2 (J − 1)² (λ or K, by form)

  static Material make(const material::ElasticParameters& elastic, material::NeoHookeanForm form);
};

Eigen::Matrix3d first_piola(const Material& m, ElementKind kind, const Eigen::Matrix3d& F);
double energy_density(const Material& m, ElementKind kind, const Eigen::Matrix3d& F);
Eigen::Matrix3d first_piola_increment(const Material& m, ElementKind kind, const Eigen::Matrix3d& F,
                                      const Eigen::Matrix3d& dF);

}  // namespace softsim::fem
