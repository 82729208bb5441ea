#include "softsim/meshless/conditioning.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace softsim::meshless {

namespace {

// A fixed, non-symmetric start vector so the iteration does not begin orthogonal to the
// extreme eigenvectors of a symmetric grid.
Eigen::VectorXd start_vector(Eigen::Index n) {
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = 1.0 + 0.5 * std::sin(1.0 + 0.37 * static_cast<double>(i));
  return v.normalized();
}

// Largest eigenvalue of a symmetric positive operator by Lanczos with full
// reorthogonalisation (the extreme Ritz value converges far faster than power iteration).
template <class Apply>
double lanczos_largest(Eigen::Index n, Apply apply, int max_iterations, double tolerance, int& used) {
  const int m_max = static_cast<int>(std::min<Eigen::Index>(n, max_iterations));
  Eigen::MatrixXd v(n, m_max + 1);
  Eigen::VectorXd alpha(m_max), beta(m_max);
  v.col(0) = start_vector(n);
  double previous = 0;
  for (int j = 0; j < m_max; ++j) {
    Eigen::VectorXd w = apply(v.col(j));
    alpha[j] = v.col(j).dot(w);
    w -= alpha[j] * v.col(j);
    if (j > 0) w -= beta[j - 1] * v.col(j - 1);
    for (int pass = 0; pass < 2; ++pass)  // full reorthogonalisation, twice is enough
      w -= v.leftCols(j + 1) * (v.leftCols(j + 1).transpose() * w);
    beta[j] = w.norm();
    Eigen::MatrixXd t = Eigen::MatrixXd::Zero(j + 1, j + 1);
    for (int i = 0; i <= j; ++i) {
      t(i, i) = alpha[i];
      if (i < j) t(i, i + 1) = t(i + 1, i) = beta[i];
    }
    const double ritz = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(t, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
    used = j + 1;
    if (j > 0 && std::abs(ritz - previous) <= tolerance * std::abs(ritz)) return ritz;
    previous = ritz;
    if (!(beta[j] > 1e-300)) return ritz;  // invariant subspace: exact
    v.col(j + 1) = w / beta[j];
  }
  return previous;
}

}  // namespace

SpectrumEstimate estimate_spectrum(const SparseMatrix& k, const StiffnessSolver& factored, int max_iterations,
                                   double tolerance) {
  SpectrumEstimate s;
  int it_max = 0, it_min = 0;
  s.lambda_max = lanczos_largest(
      k.rows(), [&](const Eigen::VectorXd& v) { return Eigen::VectorXd(k * v); }, max_iterations, tolerance, it_max);
  const double inv = lanczos_largest(
      k.rows(), [&](const Eigen::VectorXd& v) { return Eigen::VectorXd(factored.solve(v)); }, max_iterations,
      tolerance, it_min);
  s.lambda_min = inv > 0 ? 1.0 / inv : 0.0;
  s.condition = s.lambda_min > 0 ? s.lambda_max / s.lambda_min : INFINITY;
  s.iterations = std::max(it_max, it_min);
  return s;
}

SparseMatrix free_block(const SparseMatrix& k, const std::vector<int>& fixed_nodes) {
  const Eigen::Index n = k.rows();
  std::vector<int> map(n, 0);
  for (int f : fixed_nodes)
    for (int a = 0; a < 3; ++a) map[3 * f + a] = -1;
  int next = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (map[i] == 0) map[i] = next++;
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(k.nonZeros());
  for (Eigen::Index c = 0; c < n; ++c) {
    if (map[c] < 0) continue;
    for (SparseMatrix::InnerIterator it(k, c); it; ++it)
      if (map[it.row()] >= 0) trip.emplace_back(map[it.row()], map[c], it.value());
  }
  SparseMatrix out(next, next);
  out.setFromTriplets(trip.begin(), trip.end());
  return out;
}

RigidModeEnergy rigid_mode_energy(const SparseMatrix& k, const std::vector<Eigen::Vector3d>& nodes) {
  RigidModeEnergy r;
  const Eigen::Index n = k.rows();
  const double mean_diag = k.diagonal().mean();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : nodes) centroid += p;
  centroid /= static_cast<double>(nodes.size());
  for (int mode = 0; mode < 6; ++mode) {
    Eigen::VectorXd u(n);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      Eigen::Vector3d v = Eigen::Vector3d::Zero();
      if (mode < 3) v[mode] = 1.0;
      else v = Eigen::Vector3d::Unit(mode - 3).cross(nodes[i] - centroid);
      u.segment<3>(3 * i) = v;
    }
    const double energy = u.dot(k * u);
    r.ratio[mode] = std::abs(energy) / (u.squaredNorm() * mean_diag);
    r.max_ratio = std::max(r.max_ratio, r.ratio[mode]);
  }
  return r;
}

}  // namespace softsim::meshless
