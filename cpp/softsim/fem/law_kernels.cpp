#include "softsim/fem/law_kernels.hpp"

#include <algorithm>
#include <type_traits>

#include <Eigen/Core>

#include "softsim/fem/invariant_kernels.hpp"
#include "softsim/fem/kernel_macros.hpp"
#include "softsim/fem/ogden_kernels.hpp"
#include "softsim/fem/stable_kernels.hpp"

namespace softsim::fem::kernels {

namespace {

// The generic finite-strain kernel: P(F) from the law (an inline function of Law, so the
// compiler sees the whole element), ANP's averaged pressure added as p̄ cof F (cof F = J F⁻ᵀ).
// An inverted element (J ≤ 0) gets zero forces, as the corotational kernel's exact path does;
// the caller's min_j reports it. A law defined at J ≤ 0 (material::kInversionRobust, decided at
// compile time: the other laws' loops are unchanged) gets its forces there and leaves min_j
// alone, since its inverted elements are no failure.
template <class Law, bool kAveraged>
void hyperelastic_kernel(const SoaView s, const double* __restrict u, int begin, int end, const Law& law,
                         const double* __restrict pressure, double& min_j) {
  constexpr bool kRobust = material::kInversionRobust<Law>;
  double jmin = min_j;
  for (int k = begin; k < end; ++k) {
    SOFTSIM_LOAD_H(s, u, k)
    SOFTSIM_F_AND_COFACTOR
    if constexpr (!kRobust) jmin = std::min(jmin, J);
    Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
    if (kRobust || J > 0) {
      Eigen::Matrix3d F;
      F << f00, f01, f02, f10, f11, f12, f20, f21, f22;
      P = material::first_piola(law, F);
      if constexpr (kAveraged) {
        const double p = 0.25 * (pressure[a0] + pressure[a1] + pressure[a2] + pressure[a3]);
        Eigen::Matrix3d cof;
        cof << c00, c01, c02, c10, c11, c12, c20, c21, c22;
        P += p * cof;
      }
      P *= s.vol[k];
    }
    SOFTSIM_STORE_FORCES(s, k, P(0, 0), P(0, 1), P(0, 2), P(1, 0), P(1, 1), P(1, 2), P(2, 0), P(2, 1), P(2, 2))
  }
  min_j = jmin;
}

// Laws with a fibre direction per element or internal variables (law_data.hpp): the element's
// fibre replaces the law's, and a viscoelastic law advances its Prony tensors from `state_in`
// to `state_out` (material/viscoelastic.hpp). An inverted element keeps its state.
template <class Law, bool kAveraged>
void element_data_kernel(const SoaView s, const double* __restrict u, int begin, int end, const Law& law,
                         const double* __restrict pressure, const LawData& d, double& min_j) {
  constexpr bool kVisco = std::is_same_v<Law, material::Viscoelastic>;
  Law l = law;
  int n_state = 0;
  material::PronyStep step;
  if constexpr (kVisco) {
    n_state = law.state_size();
    step = material::prony_step(law, d.dt);
  }
  double jmin = min_j;
  for (int k = begin; k < end; ++k) {
    SOFTSIM_LOAD_H(s, u, k)
    SOFTSIM_F_AND_COFACTOR
    jmin = std::min(jmin, J);
    if (d.fibre[0]) {
      const Eigen::Vector3d a(d.fibre[0][k], d.fibre[1][k], d.fibre[2][k]);
      if constexpr (kVisco) material::set_fibre(l, step, a);
      else material::set_fibre(l, a);
    }
    Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
    double in[6 * material::Viscoelastic::kMaxTerms], out[6 * material::Viscoelastic::kMaxTerms];
    for (int c = 0; c < n_state; ++c) out[c] = in[c] = d.state_in[static_cast<std::size_t>(c) * d.stride + k];
    if (J > 0) {
      Eigen::Matrix3d F;
      F << f00, f01, f02, f10, f11, f12, f20, f21, f22;
      if constexpr (kVisco) P = material::relaxed_first_piola(l, step, F, in, out);
      else P = material::first_piola(l, F);
      if constexpr (kAveraged) {
        const double p = 0.25 * (pressure[a0] + pressure[a1] + pressure[a2] + pressure[a3]);
        Eigen::Matrix3d cof;
        cof << c00, c01, c02, c10, c11, c12, c20, c21, c22;
        P += p * cof;
      }
      P *= s.vol[k];
    }
    for (int c = 0; c < n_state; ++c) d.state_out[static_cast<std::size_t>(c) * d.stride + k] = out[c];
    SOFTSIM_STORE_FORCES(s, k, P(0, 0), P(0, 1), P(0, 2), P(1, 0), P(1, 1), P(1, 2), P(2, 0), P(2, 1), P(2, 2))
  }
  min_j = jmin;
}

template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

// The invariant form (invariant_kernels.hpp) of an elastic law, if it has one.
bool invariant_form(const material::ElasticLaw& law, InvariantLaw& out) {
  if (const auto* nh = std::get_if<material::NeoHookean>(&law)) {
    if (nh->form != material::NeoHookeanForm::decoupled) return false;
    out.m1 = nh->mu, out.bulk = nh->bulk;
    return true;
  }
  if (const auto* mr = std::get_if<material::MooneyRivlin>(&law)) {
    out.m1 = 2.0 * mr->c10, out.m2 = 2.0 * mr->c01, out.bulk = mr->bulk, out.has_c01 = mr->c01 != 0.0;
    return true;
  }
  if (const auto* ti = std::get_if<material::TransverselyIsotropic>(&law)) {
    out.m1 = ti->mu, out.eta = ti->eta, out.bulk = ti->bulk, out.has_fibre = true;
    for (int c = 0; c < 3; ++c) out.fibre[c] = ti->fibre[c];
    return true;
  }
  return false;
}

// A Prony series on a base with an invariant form: the fused kernel; else the generic one.
template <bool kAveraged>
void viscoelastic_forces(const material::Viscoelastic& v, const SoaView s, const double* __restrict u, int begin,
                         int end, const double* __restrict pressure, double* __restrict scratch, double& min_j,
                         const LawData& data) {
  InvariantLaw law;
  if (!invariant_form(v.base, law)) {
    element_data_kernel<material::Viscoelastic, kAveraged>(s, u, begin, end, v, pressure, data, min_j);
    return;
  }
  const material::PronyStep step = material::prony_step(v, data.dt);
  PronyTerms prony;
  prony.terms = v.terms;
  for (int i = 0; i < v.terms; ++i) prony.decay[i] = step.decay[i], prony.weight[i] = step.weight[i];
  invariant_forces(law, prony, s, u, begin, end, pressure, data, scratch, min_j);
}

}  // namespace

void tled_forces(const material::HyperelasticLaw& law, const SoaView s, const double* __restrict u, int begin,
                 int end, double* __restrict scratch, double& min_j, const LawData& data) {
  std::visit(Overloaded{[&](const material::NeoHookean& nh) {
                          if (nh.form == material::NeoHookeanForm::paper)
                            tled_paper_kernel(s, u, begin, end, nh.mu, nh.lambda, min_j);
                          else
                            tled_decoupled_kernel(s, u, begin, end, nh.mu, nh.bulk, scratch, min_j);
                        },
                        [&](const material::StableNeoHookean& sn) { tled_stable_kernel(s, u, begin, end, sn); },
                        [&](const material::MooneyRivlin& mr) {
                          InvariantLaw l;
                          invariant_form(mr, l);
                          invariant_forces(l, {}, s, u, begin, end, nullptr, data, scratch, min_j);
                        },
                        [&](const material::Ogden& og) { ogden_forces(og, s, u, begin, end, nullptr, scratch, min_j); },
                        [&](const material::TransverselyIsotropic& ti) {
                          InvariantLaw l;
                          invariant_form(ti, l);
                          invariant_forces(l, {}, s, u, begin, end, nullptr, data, scratch, min_j);
                        },
                        [&](const material::Viscoelastic& v) {
                          viscoelastic_forces<false>(v, s, u, begin, end, nullptr, scratch, min_j, data);
                        },
                        [&](const auto& other) {
                          using Law = std::decay_t<decltype(other)>;
                          hyperelastic_kernel<Law, false>(s, u, begin, end, other, nullptr, min_j);
                        }},
             law);
}

void anp_forces(const material::HyperelasticLaw& isochoric, const SoaView s, const double* __restrict u, int begin,
                int end, const double* __restrict pressure, double* __restrict scratch, double& min_j,
                const LawData& data) {
  std::visit(Overloaded{[&](const material::NeoHookean& nh) {
                          if (nh.form == material::NeoHookeanForm::paper)
                            anp_paper_kernel(s, u, begin, end, nh.mu, pressure, min_j);
                          else
                            anp_decoupled_kernel(s, u, begin, end, nh.mu, pressure, scratch, min_j);
                        },
                        [&](const material::StableNeoHookean& sn) { anp_stable_kernel(s, u, begin, end, sn, pressure); },
                        [&](const material::MooneyRivlin& mr) {
                          InvariantLaw l;
                          invariant_form(mr, l);
                          invariant_forces(l, {}, s, u, begin, end, pressure, data, scratch, min_j);
                        },
                        [&](const material::Ogden& og) { ogden_forces(og, s, u, begin, end, pressure, scratch, min_j); },
                        [&](const material::TransverselyIsotropic& ti) {
                          InvariantLaw l;
                          invariant_form(ti, l);
                          invariant_forces(l, {}, s, u, begin, end, pressure, data, scratch, min_j);
                        },
                        [&](const material::Viscoelastic& v) {
                          viscoelastic_forces<true>(v, s, u, begin, end, pressure, scratch, min_j, data);
                        },
                        [&](const auto& other) {
                          using Law = std::decay_t<decltype(other)>;
                          hyperelastic_kernel<Law, true>(s, u, begin, end, other, pressure, min_j);
                        }},
             isochoric);
}

}  // namespace softsim::fem::kernels
