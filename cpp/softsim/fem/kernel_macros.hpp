#pragma once
// The element kernels' shared pieces (element_kernels.cpp, law_kernels.cpp), as macros so that
// every kernel's loop body stays one straight block the compiler vectorises: the displacement
// gradient H of element k, F = I + H with its cofactor matrix, and the corner-force store.
// Private to the kernel sources.
#include "softsim/fem/element_kernels.hpp"

// Loads the corner displacements relative to corner 0 and forms H = Σ_b (u_b − u_0) ⊗ ∇N_b
// (the displacement gradient, 000 eq. 9 with ∇N from eq. 22). Shared by every kernel.
#define SOFTSIM_LOAD_H(s, u, k)                                                           \
  const int a0 = s.n0[k], a1 = s.n1[k], a2 = s.n2[k], a3 = s.n3[k];                       \
  const double u0x = u[a0], u0y = u[a0 + 1], u0z = u[a0 + 2];                             \
  const double d1x = u[a1] - u0x, d1y = u[a1 + 1] - u0y, d1z = u[a1 + 2] - u0z;           \
  const double d2x = u[a2] - u0x, d2y = u[a2 + 1] - u0y, d2z = u[a2 + 2] - u0z;           \
  const double d3x = u[a3] - u0x, d3y = u[a3 + 1] - u0y, d3z = u[a3 + 2] - u0z;           \
  const double g1x = s.g[0][k], g1y = s.g[1][k], g1z = s.g[2][k];                         \
  const double g2x = s.g[3][k], g2y = s.g[4][k], g2z = s.g[5][k];                         \
  const double g3x = s.g[6][k], g3y = s.g[7][k], g3z = s.g[8][k];                         \
  const double h00 = d1x * g1x + d2x * g2x + d3x * g3x;                                   \
  const double h01 = d1x * g1y + d2x * g2y + d3x * g3y;                                   \
  const double h02 = d1x * g1z + d2x * g2z + d3x * g3z;                                   \
  const double h10 = d1y * g1x + d2y * g2x + d3y * g3x;                                   \
  const double h11 = d1y * g1y + d2y * g2y + d3y * g3y;                                   \
  const double h12 = d1y * g1z + d2y * g2z + d3y * g3z;                                   \
  const double h20 = d1z * g1x + d2z * g2x + d3z * g3x;                                   \
  const double h21 = d1z * g1y + d2z * g2y + d3z * g3y;                                   \
  const double h22 = d1z * g1z + d2z * g2z + d3z * g3z;

// Corner forces f_a = M ∇N_a for a stress-like matrix M already scaled by ⁰V; corner 0 takes
// minus the sum (the gradients sum to zero).
#define SOFTSIM_STORE_FORCES(s, k, m00, m01, m02, m10, m11, m12, m20, m21, m22)             \
  {                                                                                         \
    const double M00 = (m00), M01 = (m01), M02 = (m02), M10 = (m10), M11 = (m11);           \
    const double M12 = (m12), M20 = (m20), M21 = (m21), M22 = (m22);                        \
    const double f1x = M00 * g1x + M01 * g1y + M02 * g1z;                                   \
    const double f1y = M10 * g1x + M11 * g1y + M12 * g1z;                                   \
    const double f1z = M20 * g1x + M21 * g1y + M22 * g1z;                                   \
    const double f2x = M00 * g2x + M01 * g2y + M02 * g2z;                                   \
    const double f2y = M10 * g2x + M11 * g2y + M12 * g2z;                                   \
    const double f2z = M20 * g2x + M21 * g2y + M22 * g2z;                                   \
    const double f3x = M00 * g3x + M01 * g3y + M02 * g3z;                                   \
    const double f3y = M10 * g3x + M11 * g3y + M12 * g3z;                                   \
    const double f3z = M20 * g3x + M21 * g3y + M22 * g3z;                                   \
    double* __restrict o = s.out + k;                                                       \
    const int S = s.stride;                                                                 \
    o[0] = -(f1x + f2x + f3x);                                                              \
    o[S] = -(f1y + f2y + f3y);                                                              \
    o[2 * S] = -(f1z + f2z + f3z);                                                          \
    o[3 * S] = f1x;                                                                         \
    o[4 * S] = f1y;                                                                         \
    o[5 * S] = f1z;                                                                         \
    o[6 * S] = f2x;                                                                         \
    o[7 * S] = f2y;                                                                         \
    o[8 * S] = f2z;                                                                         \
    o[9 * S] = f3x;                                                                         \
    o[10 * S] = f3y;                                                                        \
    o[11 * S] = f3z;                                                                        \
  }

// F = I + H and its cofactor matrix cof F = J F⁻ᵀ.
#define SOFTSIM_F_AND_COFACTOR                                                  \
  const double f00 = 1.0 + h00, f01 = h01, f02 = h02;                           \
  const double f10 = h10, f11 = 1.0 + h11, f12 = h12;                           \
  const double f20 = h20, f21 = h21, f22 = 1.0 + h22;                           \
  const double c00 = f11 * f22 - f12 * f21, c01 = f12 * f20 - f10 * f22;        \
  const double c02 = f10 * f21 - f11 * f20, c10 = f02 * f21 - f01 * f22;        \
  const double c11 = f00 * f22 - f02 * f20, c12 = f01 * f20 - f00 * f21;        \
  const double c20 = f01 * f12 - f02 * f11, c21 = f02 * f10 - f00 * f12;        \
  const double c22 = f00 * f11 - f01 * f10;                                     \
  const double J = f00 * c00 + f01 * c01 + f02 * c02;
