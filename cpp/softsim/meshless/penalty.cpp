#include "softsim/meshless/penalty.hpp"

#include <stdexcept>

namespace softsim::meshless {

Eigen::VectorXd apply_penalty(SparseMatrix& k, const std::vector<NodeConstraint>& constraints,
                              const PenaltyParams& params) {
  if (!(params.lambda >= 1.0)) throw std::invalid_argument("apply_penalty: lambda must be >= 1");
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(k.rows());
  if (params.kind == PenaltyParams::Kind::scale_block) {
    for (const auto& c : constraints) {
      Eigen::Matrix3d kjj = Eigen::Matrix3d::Zero();
      for (int a = 0; a < 3; ++a) {
        const int col = 3 * c.node + a;
        for (SparseMatrix::InnerIterator it(k, col); it; ++it)
          if (it.row() >= 3 * c.node && it.row() < 3 * c.node + 3) {
            kjj(it.row() - 3 * c.node, a) = it.value();
            it.valueRef() *= params.lambda;  // 002 eq. 28: λ K_jj
          }
      }
      rhs.segment<3>(3 * c.node) = params.lambda * kjj * c.value;  // 002 eq. 28: λ K_jj ū_j
    }
  } else {
    const double alpha = params.lambda * k.diagonal().cwiseAbs().maxCoeff();
    for (const auto& c : constraints)
      for (int a = 0; a < 3; ++a) {
        k.coeffRef(3 * c.node + a, 3 * c.node + a) += alpha;
        rhs[3 * c.node + a] = alpha * c.value[a];
      }
  }
  return rhs;
}

}  // namespace softsim::meshless
