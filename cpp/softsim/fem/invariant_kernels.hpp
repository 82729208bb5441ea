#pragma once
// Vectorised TLED and ANP kernels for the laws whose isochoric stress is written in the
// invariants Ī₁, Ī₂, Ī₄ (the decoupled neo-Hookean matrix, Mooney–Rivlin, the transversely
// isotropic law; material/*.hpp), optionally relaxed by a Prony series whose internal-variable
// update is fused into the element pass (material/viscoelastic.hpp). All of them have
//
//   S_iso = γ_I I + γ_C C + γ_inv C⁻¹ + γ_A a⊗a,   P = F (S_iso − Σᵢ Aᵢ) + p cof F,
//
// with b = J^(−2/3), φ = 2η (b I₄ − 1) b and, for W_iso = m₁/2 (Ī₁ − 3) + m₂/2 (Ī₂ − 3)
// + η/2 (Ī₄ − 1)² (m₁ = μ or 2 C10, m₂ = 2 C01):
//   γ_I = m₁ b + m₂ b² I₁,  γ_C = −m₂ b²,  γ_inv = −(m₁ b I₁ + 2 m₂ b² I₂ + φ I₄)/3,  γ_A = φ,
// p = K (J − 1) (TLED) or the mean of the corners' nodal pressures (ANP), F C⁻¹ = cof F / J.
// Written on the shared kernel macros like the neo-Hookean kernels, so the element loop is one
// straight block the compiler vectorises; the law's own first_piola stays the reference (tested
// to round-off against it). An inverted element (J ≤ 0) gets zero forces and keeps its state.
#include "softsim/fem/element_kernels.hpp"
#include "softsim/fem/law_data.hpp"

namespace softsim::fem::kernels {

struct InvariantLaw {
  double m1 = 0, m2 = 0, eta = 0, bulk = 0;
  double fibre[3] = {1, 0, 0};  // the law's a; LawData::fibre, where set, replaces it per element
  bool has_c01 = false;         // m₂ ≠ 0 terms are computed
  bool has_fibre = false;       // η terms are computed
};

// A Prony series' step (material::PronyStep): eᵢ and gᵢ (1 − eᵢ); terms = 0: no series.
struct PronyTerms {
  int terms = 0;
  double decay[4] = {0, 0, 0, 0};
  double weight[4] = {0, 0, 0, 0};
};

// `pressure` null: TLED with p = K (J − 1); else ANP with the corners' nodal pressures (index 3a).
// `data` the per-slot fibres and the Prony state (law_data.hpp); `scratch` one double per slot.
void invariant_forces(const InvariantLaw& law, const PronyTerms& prony, const SoaView s, const double* __restrict u,
                      int begin, int end, const double* __restrict pressure, const LawData& data,
                      double* __restrict scratch, double& min_j);

}  // namespace softsim::fem::kernels
