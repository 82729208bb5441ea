#include "softsim/fem/constitutive.hpp"

#include "softsim/material/small_strain.hpp"

namespace softsim::fem {

Material Material::make(const material::ElasticParameters& elastic, material::NeoHookeanForm form) {
  material::validate(elastic);
  return make(elastic, material::NeoHookean::from(form, elastic));
}

Material Material::make(const material::ElasticParameters& elastic, const material::HyperelasticLaw& law) {
  material::validate(elastic);
  Material m;
  m.elastic = elastic;
  m.lame = material::lame_parameters(elastic);
  m.law = law;
  m.isochoric = material::isochoric_part(law);
  m.volumetric_modulus = material::volumetric_modulus(law);
  return m;
}

Eigen::Vector3d Material::fibre(int e) const {
  if (fibres) return (*fibres)[static_cast<std::size_t>(e)];
  const Eigen::Vector3d* a = material::fibre_of(law);
  return a ? *a : Eigen::Vector3d::Zero();
}

Material Material::for_element(int e) const {
  Material m = *this;
  if (fibres) {
    material::set_fibre(m.law, fibre(e));
    material::set_fibre(m.isochoric, fibre(e));
  }
  return m;
}

Eigen::Matrix3d first_piola(const Material& m, ElementKind kind, const Eigen::Matrix3d& F) {
  switch (kind) {
    case ElementKind::linear: return material::linear_stress(m.lame, F);
    case ElementKind::tled: return material::first_piola(m.law, F);
    case ElementKind::corotational: return material::corotated_first_piola(m.lame, F);
    case ElementKind::anp:
    case ElementKind::smoothed: return material::first_piola(m.isochoric, F);
  }
  return Eigen::Matrix3d::Zero();
}

double energy_density(const Material& m, ElementKind kind, const Eigen::Matrix3d& F) {
  switch (kind) {
    case ElementKind::linear: return material::linear_energy_density(m.lame, F);
    case ElementKind::tled: return material::strain_energy_density(m.law, F);
    case ElementKind::corotational: return material::corotated_energy_density(m.lame, F);
    case ElementKind::anp:
    case ElementKind::smoothed: return material::strain_energy_density(m.isochoric, F);
  }
  return 0.0;
}

FirstPiolaLinearisation::FirstPiolaLinearisation(const Material& m, ElementKind kind, const Eigen::Matrix3d& F)
    : material_(m), kind_(kind) {
  switch (kind) {
    case ElementKind::linear: break;  // dP does not depend on F
    case ElementKind::tled: law_ = material::linearise(m.law, F); break;
    case ElementKind::corotational: corotated_ = material::corotated_linearise(F); break;
    case ElementKind::anp:
    case ElementKind::smoothed: law_ = material::linearise(m.isochoric, F); break;
  }
}

Eigen::Matrix3d FirstPiolaLinearisation::increment(const Eigen::Matrix3d& dF) const {
  const Material& m = material_;
  switch (kind_) {
    case ElementKind::linear: return material::linear_stress_increment(m.lame, dF);
    case ElementKind::tled: return material::first_piola_increment(m.law, law_, dF);
    case ElementKind::corotational: return material::corotated_first_piola_increment(m.lame, corotated_, dF);
    case ElementKind::anp:
    case ElementKind::smoothed: return material::first_piola_increment(m.isochoric, law_, dF);
  }
  return Eigen::Matrix3d::Zero();
}

}  // namespace softsim::fem
