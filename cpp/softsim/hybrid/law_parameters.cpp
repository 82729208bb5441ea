#include "softsim/hybrid/law_parameters.hpp"

#include <vector>

namespace softsim::hybrid {

namespace {

template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

void add_elastic(const material::ElasticLaw& law, bool per_element_fibres, nlohmann::json& out) {
  std::visit(Overloaded{[&](const material::NeoHookean&) {},
                        [&](const material::MooneyRivlin& mr) {
                          out["C10"] = mr.c10;
                          out["C01"] = mr.c01;
                        },
                        [&](const material::Ogden& og) {
                          out["mu_p"] = std::vector<double>(og.mu.begin(), og.mu.begin() + og.terms);
                          out["alpha_p"] = std::vector<double>(og.alpha.begin(), og.alpha.begin() + og.terms);
                        },
                        [&](const material::TransverselyIsotropic& ti) {
                          out["mu_matrix"] = ti.mu;
                          out["eta"] = ti.eta;
                          if (per_element_fibres) out["fibres"] = "per_element";
                          else out["fibre"] = {ti.fibre.x(), ti.fibre.y(), ti.fibre.z()};
                        }},
             law);
}

}  // namespace

double bulk_modulus(const fem::Material& m) {
  const auto bulk = [&](const auto& l) -> double {
    using Law = std::decay_t<decltype(l)>;
    if constexpr (std::is_same_v<Law, material::Viscoelastic>)
      return std::visit([](const auto& b) { return b.bulk; }, l.base);
    else if constexpr (std::is_same_v<Law, material::StableNeoHookean>)
      return material::bulk_modulus(m.elastic);
    else
      return l.bulk;
  };
  return std::visit(bulk, m.law);
}

void add_law_parameters(const fem::Material& m, nlohmann::json& out) {
  const bool per_element = m.fibres != nullptr;
  std::visit(Overloaded{[&](const material::Viscoelastic& v) {
                          out["prony_g"] = std::vector<double>(v.g.begin(), v.g.begin() + v.terms);
                          out["prony_tau"] = std::vector<double>(v.tau.begin(), v.tau.begin() + v.terms);
                          out["g_inf"] = v.long_term();
                          add_elastic(v.base, per_element, out);
                        },
                        [&](const material::StableNeoHookean& sn) {
                          out["mu_stable"] = sn.mu;
                          out["lambda_stable"] = sn.lambda;
                        },
                        [&](const auto& l) { add_elastic(l, per_element, out); }},
             m.law);
}

}  // namespace softsim::hybrid
