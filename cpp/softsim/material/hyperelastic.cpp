#include "softsim/material/hyperelastic.hpp"

#include <type_traits>
#include <utility>

namespace softsim::material {

std::string law_name(const HyperelasticLaw& law) {
  return std::visit([](const auto& l) { return law_name(l); }, law);
}

double strain_energy_density(const HyperelasticLaw& law, const Eigen::Matrix3d& F) {
  return std::visit([&](const auto& l) { return strain_energy_density(l, F); }, law);
}

Eigen::Matrix3d second_piola(const HyperelasticLaw& law, const Eigen::Matrix3d& C) {
  return std::visit([&](const auto& l) -> Eigen::Matrix3d { return second_piola(l, C); }, law);
}

Eigen::Matrix3d first_piola(const HyperelasticLaw& law, const Eigen::Matrix3d& F) {
  return std::visit([&](const auto& l) -> Eigen::Matrix3d { return first_piola(l, F); }, law);
}

HyperelasticLinearisation linearise(const HyperelasticLaw& law, const Eigen::Matrix3d& F) {
  return std::visit([&](const auto& l) -> HyperelasticLinearisation { return linearise(l, F); }, law);
}

Eigen::Matrix3d first_piola_increment(const HyperelasticLaw& law, const HyperelasticLinearisation& at,
                                      const Eigen::Matrix3d& dF) {
  // `at` was made by linearise(law, ·): its alternative is the one the law's linearise returns.
  return std::visit(
      [&](const auto& l) -> Eigen::Matrix3d {
        using Linearisation = decltype(linearise(l, dF));
        return first_piola_increment(l, std::get<Linearisation>(at), dF);
      },
      law);
}

double volumetric_modulus(const HyperelasticLaw& law) {
  return std::visit([](const auto& l) { return volumetric_modulus(l); }, law);
}

HyperelasticLaw isochoric_part(const HyperelasticLaw& law) {
  return std::visit([](const auto& l) -> HyperelasticLaw { return isochoric_part(l); }, law);
}

bool inversion_robust(const HyperelasticLaw& law) {
  return std::visit([](const auto& l) { return kInversionRobust<std::decay_t<decltype(l)>>; }, law);
}

const Eigen::Vector3d* fibre_of(const HyperelasticLaw& law) {
  if (const auto* ti = std::get_if<TransverselyIsotropic>(&law)) return &ti->fibre;
  if (const auto* v = std::get_if<Viscoelastic>(&law)) return fibre_of(*v);
  return nullptr;
}

void set_fibre(HyperelasticLaw& law, const Eigen::Vector3d& a) {
  if (auto* ti = std::get_if<TransverselyIsotropic>(&law)) ti->fibre = a;
  if (auto* v = std::get_if<Viscoelastic>(&law)) set_fibre(*v, a);
}

int state_size(const HyperelasticLaw& law) {
  const auto* v = std::get_if<Viscoelastic>(&law);
  return v ? v->state_size() : 0;
}

}  // namespace softsim::material
