#pragma once
// Essential boundary conditions by the penalty method (002 eqs. 28–29).
// Because RPIM shape functions interpolate (φ_I(x_J) = δ_IJ), a prescribed displacement of a
// node is a condition on its own three degrees of freedom, imposed on K directly.
#include <vector>

#include <Eigen/Core>

#include "softsim/meshless/assembly.hpp"

namespace softsim::meshless {

struct PenaltyParams {
  enum class Kind {
    scale_block,   // 002 eq. 28: K_JJ <- λ K_JJ, F_J = λ K_JJ ū_J (λ is already relative)
    add_diagonal,  // K_JJ <- K_JJ + α I, F_J += α ū_J with α = λ · max_i K_ii
  };
  Kind kind = Kind::scale_block;
  double lambda = 1e7;  // 002: λ >= 1e7
};

struct NodeConstraint {
  int node = 0;
  Eigen::Vector3d value = Eigen::Vector3d::Zero();  // ū (m)
};

// Modifies K in place and returns the constant right-hand side the constraints add to every
// load case (zero for homogeneous conditions).
Eigen::VectorXd apply_penalty(SparseMatrix& k, const std::vector<NodeConstraint>& constraints,
                              const PenaltyParams& params);

}  // namespace softsim::meshless
