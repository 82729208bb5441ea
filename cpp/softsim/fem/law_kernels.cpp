#include "softsim/fem/law_kernels.hpp"

#include <algorithm>
#include <type_traits>

#include <Eigen/Core>

#include "softsim/fem/kernel_macros.hpp"
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
                        [&](const material::TransverselyIsotropic& ti) {
                          element_data_kernel<material::TransverselyIsotropic, false>(s, u, begin, end, ti, nullptr,
                                                                                      data, min_j);
                        },
                        [&](const material::Viscoelastic& v) {
                          element_data_kernel<material::Viscoelastic, false>(s, u, begin, end, v, nullptr, data, min_j);
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
                        [&](const material::TransverselyIsotropic& ti) {
                          element_data_kernel<material::TransverselyIsotropic, true>(s, u, begin, end, ti, pressure,
                                                                                     data, min_j);
                        },
                        [&](const material::Viscoelastic& v) {
                          element_data_kernel<material::Viscoelastic, true>(s, u, begin, end, v, pressure, data, min_j);
                        },
                        [&](const auto& other) {
                          using Law = std::decay_t<decltype(other)>;
                          hyperelastic_kernel<Law, true>(s, u, begin, end, other, pressure, min_j);
                        }},
             isochoric);
}

}  // namespace softsim::fem::kernels
