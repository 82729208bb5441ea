#pragma once
// One material seen by every element kind: linear and corotational elements use the
// small-strain law with (μ, λ); TLED elements use the chosen neo-Hookean form with the same
// (E, ν); ANP elements its isochoric part only — their volumetric part U(J) lives at the nodes
// (nodal_pressure.hpp). Everything element-local is expressed as P(F), W(F) and dP(F)[dF].
#include <Eigen/Core>

#include "softsim/fem/element_kind.hpp"
#include "softsim/material/elastic.hpp"
#include "softsim/material/neo_hookean.hpp"
#include "softsim/material/small_strain.hpp"

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

// dP(F)[dF] for many dF at one F (the 12 columns of an element tangent), with the set-up that
// depends on F alone done once: the polar decomposition and (tr(S) I − S)⁻¹ of the corotational
// kind, J^(−2/3) of the decoupled neo-Hookean form (material/*.hpp). Each dP is bit for bit the
// one-shot first_piola_increment's. Holds a reference to the material.
class FirstPiolaLinearisation {
 public:
  FirstPiolaLinearisation(const Material& m, ElementKind kind, const Eigen::Matrix3d& F);
  Eigen::Matrix3d increment(const Eigen::Matrix3d& dF) const;

 private:
  const Material& material_;
  ElementKind kind_;
  material::NeoHookeanLinearisation neo_hookean_;  // tled, anp
  material::CorotatedLinearisation corotated_;     // corotational
};

}  // namespace softsim::fem
