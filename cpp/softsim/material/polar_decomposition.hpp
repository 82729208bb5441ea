#pragma once
// Polar decomposition F = R S (R a rotation, S symmetric positive definite) by Higham's scaled
// Newton iteration X ← (γ X + X⁻ᵀ/γ)/2, which converges quadratically from X₀ = F for any
// det F > 0. Used by the corotational element (rotation of its frame) and by strain measures.
#include <cmath>

#include <Eigen/Core>

namespace softsim::material {

struct Polar {
  Eigen::Matrix3d R;
  Eigen::Matrix3d S;
  int iterations = 0;
};

// Requires det F > 0 (an inverted element has no proper rotation; callers check J first).
inline Polar polar_decomposition(const Eigen::Matrix3d& F) {
  Eigen::Matrix3d X = F;
  int it = 0;
  bool scale = true;
  for (; it < 40; ++it) {
    // X⁻ᵀ = cof(X) / det X.
    Eigen::Matrix3d cof;
    cof(0, 0) = X(1, 1) * X(2, 2) - X(1, 2) * X(2, 1);
    cof(0, 1) = X(1, 2) * X(2, 0) - X(1, 0) * X(2, 2);
    cof(0, 2) = X(1, 0) * X(2, 1) - X(1, 1) * X(2, 0);
    cof(1, 0) = X(0, 2) * X(2, 1) - X(0, 1) * X(2, 2);
    cof(1, 1) = X(0, 0) * X(2, 2) - X(0, 2) * X(2, 0);
    cof(1, 2) = X(0, 1) * X(2, 0) - X(0, 0) * X(2, 1);
    cof(2, 0) = X(0, 1) * X(1, 2) - X(0, 2) * X(1, 1);
    cof(2, 1) = X(0, 2) * X(1, 0) - X(0, 0) * X(1, 2);
    cof(2, 2) = X(0, 0) * X(1, 1) - X(0, 1) * X(1, 0);
    const double det = X(0, 0) * cof(0, 0) + X(0, 1) * cof(0, 1) + X(0, 2) * cof(0, 2);
    const Eigen::Matrix3d XinvT = cof / det;
    double gamma = 1.0;
    if (scale) gamma = std::sqrt(std::sqrt(XinvT.squaredNorm() / X.squaredNorm()));
    const Eigen::Matrix3d next = 0.5 * (gamma * X + XinvT / gamma);
    const double change = (next - X).squaredNorm();
    X = next;
    if (change < 1e-4) scale = false;  // near convergence plain Newton is quadratic
    if (change < 1e-30) {
      ++it;
      break;
    }
  }
  Polar p;
  p.R = X;
  const Eigen::Matrix3d S = X.transpose() * F;
  p.S = 0.5 * (S + S.transpose());
  p.iterations = it;
  return p;
}

}  // namespace softsim::material
