#pragma once
// The homogeneous solution of uniaxial stress (a block stretched by λₐ along one axis with
// traction-free lateral faces): F = diag(λₜ, λₜ, λₐ). Written out from each law's strain
// energy independently of the stress code, so tests can compare the finite elements with it.
#include "softsim/material/elastic.hpp"
#include "softsim/material/neo_hookean.hpp"

namespace softsim::material {

struct UniaxialSolution {
  double axial_stretch = 1;    // λₐ (imposed)
  double lateral_stretch = 1;  // λₜ making the lateral stress vanish
  double nominal_stress = 0;   // P₃₃: axial force per reference area (Pa)
};

// Paper form: λₜ² solves λ λₐ² s² + (μ − λ λₐ) s − μ = 0 (from P₁₁ = 0), closed form.
// Decoupled form: μ J^(−2/3) (λₜ² − λₐ²)/3 + K J (J − 1) = 0 with J = λₜ² λₐ, bisection.
UniaxialSolution uniaxial_neo_hookean(const NeoHookean& law, double axial_stretch);
// Small-strain elasticity: λₜ = 1 − ν (λₐ − 1), P₃₃ = E (λₐ − 1).
UniaxialSolution uniaxial_linear(const ElasticParameters& p, double axial_stretch);

}  // namespace softsim::material
