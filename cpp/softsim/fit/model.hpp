#pragma once
// A fitted surface model: the three relations of 002 §3 for each load direction.
//
//   relation 1 (002 eqs. 39–42):  δ_d = g_d(F_d)                 loaded-node displacement
//   relation 3 (002 eqs. 45–46):  p_{d,c} = ρ_{d,c}(δ_d)         surface coefficients
//   relation 2 (002 eq. 44):      u_c(x, y) += Σ_k p_{d,c,k} ψ_k(x, y)
//
// for load direction d and displacement component c. A composite force is played back as the
// sum over its components (002 §5.1.1, Fig. 14: each original displacement from eq. 49).
#include <array>

#include <Eigen/Dense>

#include "softsim/fit/basis.hpp"
#include "softsim/fit/surface_basis.hpp"

namespace softsim::fit {

// Names of the load directions d and displacement components c = 0, 1, 2 (artifact keys, messages).
inline constexpr const char* kAxis[3] = {"x", "y", "z"};

struct ComponentModel {
  SurfaceTerms surface;     // relation 2
  int parameter_order = 0;  // k of relation 3
  // beta(k, m): coefficient of φ_m(sδ) in surface coefficient p_k (terms × (parameter_order + 1)).
  Eigen::MatrixXd beta;
};

struct DirectionModel {
  bool present = false;
  Polynomial1D force_to_loaded;  // relation 1, F_d (N) -> δ_d (m)
  AffineScale delta_scale;       // sδ = delta_scale.to_unit(δ_d) in relation 3
  std::array<ComponentModel, 3> components;
};

struct FitModel {
  SurfaceFrame frame;
  bool scaled_inputs = true;  // false: the raw SI variables were used (no mapping to [-1, 1])
  Eigen::MatrixXd nodes;      // surface nodes × 3, m
  int loaded_node = 0;        // 0-based
  // 002 §5.1.1 (Fig. 14): "we directly substituted the displacement computed by Eq. (49) for
  // Δx61, Δy61, Δz61": the loaded node's displacement along d under the force along d is δ_d of
  // relation 1 instead of the value of the surface polynomial there (a point load makes a peak
  // that low-order surfaces smooth out). Contributions across directions stay the surfaces'.
  bool loaded_node_from_relation1 = true;
  std::array<DirectionModel, 3> directions;
};

}  // namespace softsim::fit
