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

template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

}  // namespace

void tled_forces(const material::HyperelasticLaw& law, const SoaView s, const double* __restrict u, int begin,
                 int end, double* __restrict scratch, double& min_j) {
  std::visit(Overloaded{[&](const material::NeoHookean& nh) {
                          if (nh.form == material::NeoHookeanForm::paper)
                            tled_paper_kernel(s, u, begin, end, nh.mu, nh.lambda, min_j);
                          else
                            tled_decoupled_kernel(s, u, begin, end, nh.mu, nh.bulk, scratch, min_j);
                        },
                        [&](const material::StableNeoHookean& sn) { tled_stable_kernel(s, u, begin, end, sn); },
                        [&](const auto& other) {
                          using Law = std::decay_t<decltype(other)>;
                          hyperelastic_kernel<Law, false>(s, u, begin, end, other, nullptr, min_j);
                        }},
             law);
}

void anp_forces(const material::HyperelasticLaw& isochoric, const SoaView s, const double* __restrict u, int begin,
                int end, const double* __restrict pressure, double* __restrict scratch, double& min_j) {
  std::visit(Overloaded{[&](const material::NeoHookean& nh) {
                          if (nh.form == material::NeoHookeanForm::paper)
                            anp_paper_kernel(s, u, begin, end, nh.mu, pressure, min_j);
                          else
                            anp_decoupled_kernel(s, u, begin, end, nh.mu, pressure, scratch, min_j);
                        },
                        [&](const material::StableNeoHookean& sn) { anp_stable_kernel(s, u, begin, end, sn, pressure); },
                        [&](const auto& other) {
                          using Law = std::decay_t<decltype(other)>;
                          hyperelastic_kernel<Law, true>(s, u, begin, end, other, pressure, min_j);
                        }},
             isochoric);
}

}  // namespace softsim::fem::kernels
