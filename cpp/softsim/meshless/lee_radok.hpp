#pragma once
// The indentation modulus of 002 §4.1 (eqs. 47–48): a spherical probe of radius R pressed to
// depth δ with force F gives, by Lee and Radok,
//   G = 3 F / (16 δ √(R δ))          002 eq. 47
//   E = 2 G (1 + ν)                   002 eq. 48
// (for an incompressible half-space this is Hertz's F = (16/3) G √R δ^(3/2)).
namespace softsim::meshless {

struct IndentationModulus {
  double shear_modulus = 0;   // Pa
  double youngs_modulus = 0;  // Pa
};

// SI inputs (N, m, m). Throws std::invalid_argument for non-positive inputs.
IndentationModulus lee_radok_modulus(double force, double depth, double probe_radius, double poisson_ratio);

}  // namespace softsim::meshless
