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

}  // namespace softsim::material
