#pragma once
// Verification problems on a block with a known displacement field, all boundary nodes held at
// the exact values by the penalty method:
//   linear_patch   u = u₀ + G x (constant strain, no body force): the patch test
//   plane_wave     u = c sin(a·x), body force b = [(λ+μ)(c·a) a + μ|a|² c] sin(a·x),
//                  which satisfies Lᵀσ + b = 0 (002 eq. 1) exactly: a convergence test
#include <Eigen/Core>

#include "softsim/meshless/rpim_model.hpp"

namespace softsim::meshless {

enum class ManufacturedField { linear_patch, plane_wave };

struct BlockStudy {
  ManufacturedField field = ManufacturedField::plane_wave;
  double edge = 1.0;            // cube edge (m)
  int nodes_per_edge = 5;
  int cells_per_edge = 4;
  int gauss_order = 3;  // per direction per cell (rpim_precompute.md: block.gauss_order)
  double youngs_modulus = 1000.0;
  double poisson_ratio = 0.3;
};

struct BlockStudyResult {
  int nodes = 0;
  double spacing = 0;           // m
  double max_error = 0;         // max nodal |u - u_exact| over all nodes
  double rms_error = 0;         // root mean square nodal error
  double reference = 0;         // max nodal |u_exact|
  double relative_rms() const { return rms_error / reference; }
  double relative_max() const { return max_error / reference; }
};

Eigen::Vector3d manufactured_displacement(ManufacturedField field, double edge, const Eigen::Vector3d& x);

BlockStudyResult run_block_study(const BlockStudy& study, const RpimSettings& settings);

}  // namespace softsim::meshless
