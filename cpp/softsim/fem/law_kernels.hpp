#pragma once
// The finite-strain element kernels (TLED, ANP) for a material's hyperelastic law
// (material/hyperelastic.hpp). The law is chosen here, once per range of elements; below that
// it is a template parameter of the element loop, so there is no switch or virtual call per
// element. Every law of the variant has a vectorised kernel: the neo-Hookean forms their
// hand-written ones (element_kernels.hpp), the stable neo-Hookean law its own (stable_kernels.hpp),
// Mooney–Rivlin, the transversely isotropic law and Prony series on those bases the invariant-form
// kernel (invariant_kernels.hpp), Ogden the closed-form principal-stretch kernel
// (ogden_kernels.hpp). A Prony series on an Ogden base, and any law added later, runs the generic
// kernel, which asks the law for P(F) element by element (forces ⁰V P ∇N, 000 eq. 13 written with
// P = F S).
#include "softsim/fem/element_kernels.hpp"
#include "softsim/fem/law_data.hpp"
#include "softsim/material/hyperelastic.hpp"

namespace softsim::fem::kernels {

// TLED with `law`. `scratch` (one per slot) is the kernels' fix-up scratch (element_kernels.hpp);
// `data` the fibres and internal variables of a law that has them (law_data.hpp), else empty.
void tled_forces(const material::HyperelasticLaw& law, const SoaView s, const double* __restrict u, int begin,
                 int end, double* __restrict scratch, double& min_j, const LawData& data = {});

// ANP with `isochoric`, the law's isochoric part (material::isochoric_part): ⁰V (P_iso(F) + p̄ cof F) ∇N
// with p̄ the mean of the corners' nodal pressures (`pressure`, p_a at index 3a).
void anp_forces(const material::HyperelasticLaw& isochoric, const SoaView s, const double* __restrict u, int begin,
                int end, const double* __restrict pressure, double* __restrict scratch, double& min_j,
                const LawData& data = {});

}  // namespace softsim::fem::kernels
