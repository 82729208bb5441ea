#pragma once
// The vectorised element kernels of the explicit engine (used by ElementSet): each computes the
// 12 corner forces of the elements [begin, end) of one kind from the nodal displacements and
// writes them component-major into `out` (component c of slot k at out[c * stride + k]).
// Ranges must be whole blocks of ElementSet's padding so that every element takes the same
// (vector) code path whatever the split into threads.
namespace softsim::fem::kernels {

struct SoaView {
  const int* __restrict n0;  // 3 × node index of each corner
  const int* __restrict n1;
  const int* __restrict n2;
  const int* __restrict n3;
  const double* __restrict g[9];  // ∇N of corners 1..3, (x, y, z) each
  const double* __restrict vol;   // ⁰V
  double* __restrict out;
  int stride;
};

// Small strain: ⁰V σ(sym ∇u) ∇N (000 eqs. 9–12).
void linear_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu, double lambda);

// TLED, paper form (000 eqs. 13–14). min_j: lowered to the smallest det F seen.
void tled_paper_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu, double lambda,
                       double& min_j);

// TLED, decoupled form. `volume_ratio` (one per slot) is scratch for the exact-root fix-up.
void tled_decoupled_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu, double bulk,
                           double* __restrict volume_ratio, double& min_j);

// ANP (nodal_pressure.hpp): TLED of either form with the volumetric term replaced by the mean
// of the corners' nodal pressures; `pressure` holds p_a at index 3a (the corners' offsets).
void anp_paper_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu,
                      const double* __restrict pressure, double& min_j);
void anp_decoupled_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu,
                          const double* __restrict pressure, double* __restrict volume_ratio, double& min_j);

// det F of each element into volume_ratio[k] (the ANP pre-pass); nothing is written to s.out.
void volume_ratio_kernel(const SoaView s, const double* __restrict u, int begin, int end,
                         double* __restrict volume_ratio, double& min_j);

// Corotational. `last_update` (one per slot) is scratch for the polar-decomposition fix-up: the
// kernel stores 0 (converged) or 1 (recompute on the exact path) per element.
void corotational_kernel(const SoaView s, const double* __restrict u, int begin, int end, double mu, double lambda,
                         double* __restrict last_update, double& min_j);

}  // namespace softsim::fem::kernels
