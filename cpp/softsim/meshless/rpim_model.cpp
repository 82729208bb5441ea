#include "softsim/meshless/rpim_model.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "softsim/io/errors.hpp"

namespace softsim::meshless {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

RbfParams resolve_rbf(const RpimSettings& settings, double mean_spacing) {
  RbfParams rbf;
  rbf.alpha_c = settings.alpha_c;
  rbf.q = settings.q;
  rbf.d_c = settings.d_c.resolve(mean_spacing);
  rbf.polynomial = settings.polynomial;
  rbf.max_moment_condition = settings.max_moment_condition;
  rbf.max_partition_error = settings.max_partition_error;
  return rbf;
}

SupportRule resolve_support(const RpimSettings& settings, double mean_spacing) {
  SupportRule support;
  support.kind = settings.support;
  support.radius = settings.support_radius.resolve(mean_spacing);
  support.count = settings.support_count;
  return support;
}

RpimModel::RpimModel(const MeshlessProblem& problem, const RpimSettings& settings)
    : problem_(problem), solver_(settings.solver) {
  if (problem_.nodes.empty()) throw std::invalid_argument("RpimModel: no nodes");
  const bool given_points = !problem_.quadrature.points.empty();
  double volume = problem_.size.prod();
  if (given_points) {
    volume = 0;
    for (double w : problem_.quadrature.weights) volume += w;
  }
  spacing_ = problem_.mean_spacing > 0 ? problem_.mean_spacing
                                       : std::cbrt(volume / static_cast<double>(problem_.nodes.size()));
  rbf_ = resolve_rbf(settings, spacing_);
  support_ = resolve_support(settings, spacing_);
  material_ = lame_from_young(problem_.youngs_modulus, problem_.poisson_ratio);

  auto t0 = std::chrono::steady_clock::now();
  shapes_ = build_shape_table(
      problem_.nodes,
      given_points ? problem_.quadrature
                   : box_quadrature(problem_.origin, problem_.size, problem_.cells, problem_.gauss_order),
      support_, rbf_);
  timings_.shape_functions_s = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  k_free_ = assemble_stiffness(shapes_, num_nodes(), material_);
  timings_.assembly_s = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  k_ = k_free_;
  penalty_rhs_ = apply_penalty(k_, problem_.constraints, settings.penalty);
  timings_.penalty_s = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  solver_.factorize(k_, k_free_.diagonal().cwiseAbs().maxCoeff());
  timings_.factorisation_s = seconds_since(t0);
}

Eigen::MatrixXd RpimModel::solve(const Eigen::MatrixXd& nodal_forces) const {
  if (nodal_forces.rows() != 3 * num_nodes()) throw std::invalid_argument("RpimModel::solve: wrong force size");
  Eigen::MatrixXd rhs = nodal_forces;
  if (penalty_rhs_.squaredNorm() > 0) rhs.colwise() += penalty_rhs_;
  return solver_.solve(rhs);
}

Eigen::VectorXd RpimModel::body_force(const BodyForceField& b) const {
  return assemble_body_force(shapes_, num_nodes(), b);
}

}  // namespace softsim::meshless
