#pragma once
// The fitted relations re-expressed as the paper writes them: plain monomials in millimetres and
// newtons, x and y (and z, for trivariate surfaces) measured from the smallest node coordinate
// (the plate corner, 002 §3.2: 0 <= x, y <= 48 mm), so that our
// coefficients can be set beside 002 eq. 49 and Tables 1–2. For display only: playback uses the
// scaled basis, which is better conditioned.
#include <array>
#include <vector>

#include <Eigen/Dense>

#include "softsim/fit/model.hpp"

namespace softsim::fit {

// δ [mm] = Σ_k r_k F^k [N] (002 eqs. 40–42, 49).
Eigen::VectorXd force_relation_in_mm(const DirectionModel& direction);

struct PaperSurface {
  std::vector<std::array<int, 3>> powers;  // (x, y, z powers) of each surface term, paper order
  // beta(t, q): coefficient of δ[mm]^q in the coefficient of term t (displacement in mm,
  // x, y in mm): p_t = Σ_q beta(t, q) δ^q (002 eq. 46 and Tables 1–2: β1, β2, ...).
  Eigen::MatrixXd beta;
};

PaperSurface surface_in_mm(const FitModel& model, int direction, int component);

}  // namespace softsim::fit
