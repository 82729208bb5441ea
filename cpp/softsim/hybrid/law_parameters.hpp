#pragma once
// The material block of the dhd_result artifact beyond (E, ν, ρ): each law's own parameters.
#include <nlohmann/json.hpp>

#include "softsim/fem/constitutive.hpp"

namespace softsim::hybrid {

// K of the law (λ + 2μ/3 for the paper's neo-Hookean form); a Prony series: its base's; the
// stable neo-Hookean law has none of its own (Smith et al.'s λ is not a bulk modulus): the
// small-strain K it linearises to.
double bulk_modulus(const fem::Material& m);

// C10, C01 (Mooney–Rivlin); mu_p, alpha_p (Ogden); mu_stable, lambda_stable (Smith et al.'s
// (μ, λ) of the stable neo-Hookean law); mu_matrix, eta and the fibre or
// "fibres": "per_element" (transversely isotropic); prony_g, prony_tau, g_inf and the base's
// (a Prony series).
void add_law_parameters(const fem::Material& m, nlohmann::json& out);

}  // namespace softsim::hybrid
