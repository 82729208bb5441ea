#pragma once
// One material seen by every element formulation (element_kind.hpp): the constitutive law is
// chosen apart from the formulation. TLED elements use the material's hyperelastic law
// (material/hyperelastic.hpp: neo-Hookean in either form, Mooney–Rivlin, Ogden, ...); ANP
// elements its isochoric part only — their volumetric part U(J) lives at the nodes (nodal_pressure.hpp);
// linear and corotational elements use the small-strain law with the (μ, λ) the law linearises
// to. Everything element-local is expressed as P(F), W(F) and dP(F)[dF].
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "softsim/fem/element_kind.hpp"
#include "softsim/material/elastic.hpp"
#include "softsim/material/hyperelastic.hpp"
#include "softsim/material/small_strain.hpp"

namespace softsim::fem {

struct Material {
  material::ElasticParameters elastic;  // small-strain (E, ν) the law linearises to, and ρ
  material::LameParameters lame;
  material::HyperelasticLaw law;        // tled
  material::HyperelasticLaw isochoric;  // law without its volumetric term (anp)
  double volumetric_modulus = 0;        // κ of U(J) = κ/2 (J − 1)² (λ or K, by law)
  // A law with a fibre direction (material::fibre_of): one unit direction per element, which
  // replaces the law's own; null: the law's direction for every element.
  std::shared_ptr<const std::vector<Eigen::Vector3d>> fibres;

  // The fibre of element e (the law's own without `fibres`; zero for an isotropic law).
  Eigen::Vector3d fibre(int e) const;
  // This material as element e sees it: its law with element e's fibre (a copy of *this when
  // there are no per-element fibres). For the one-element-at-a-time paths (static solver,
  // stress and energy outputs); the explicit kernels read the fibres from the element set.
  Material for_element(int e) const;

  // The neo-Hookean law of the given form with (E, ν).
  static Material make(const material::ElasticParameters& elastic, material::NeoHookeanForm form);
  // Any law; `elastic` must be the (E, ν) it linearises to (and the density).
  static Material make(const material::ElasticParameters& elastic, const material::HyperelasticLaw& law);
};

// Calls f(material) with the material element e sees: `m` itself, or its copy with element e's
// fibre when it has per-element fibres.
template <class Fn>
decltype(auto) with_element_material(const Material& m, int e, Fn&& f) {
  if (!m.fibres) return f(m);
  return f(m.for_element(e));
}

Eigen::Matrix3d first_piola(const Material& m, ElementKind kind, const Eigen::Matrix3d& F);
double energy_density(const Material& m, ElementKind kind, const Eigen::Matrix3d& F);

// dP(F)[dF] for many dF at one F (the 12 columns of an element tangent), with the set-up that
// depends on F alone done once: the polar decomposition and (tr(S) I − S)⁻¹ of the corotational
// kind, the law's own (material::linearise). Each dP is bit for bit the one-shot
// increment's. Holds a reference to the material.
class FirstPiolaLinearisation {
 public:
  FirstPiolaLinearisation(const Material& m, ElementKind kind, const Eigen::Matrix3d& F);
  Eigen::Matrix3d increment(const Eigen::Matrix3d& dF) const;

 private:
  const Material& material_;
  ElementKind kind_;
  material::HyperelasticLinearisation law_;     // tled, anp
  material::CorotatedLinearisation corotated_;  // corotational
};

}  // namespace softsim::fem
