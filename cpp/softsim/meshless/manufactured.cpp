#include "softsim/meshless/manufactured.hpp"

#include <cmath>

namespace softsim::meshless {

namespace {

const double kPi = std::acos(-1.0);

Eigen::Vector3d wave_vector(double edge) { return Eigen::Vector3d(1.1, 0.7, 0.9) * kPi / edge; }
Eigen::Vector3d amplitude(double edge) { return Eigen::Vector3d(1.0, -0.5, 0.8) * 1e-3 * edge; }

Eigen::Vector3d body_force(const LameParameters& m, double edge, const Eigen::Vector3d& x) {
  const Eigen::Vector3d a = wave_vector(edge), c = amplitude(edge);
  return ((m.lambda + m.mu) * c.dot(a) * a + m.mu * a.squaredNorm() * c) * std::sin(a.dot(x));
}

}  // namespace

Eigen::Vector3d manufactured_displacement(ManufacturedField field, double edge, const Eigen::Vector3d& x) {
  if (field == ManufacturedField::plane_wave) return amplitude(edge) * std::sin(wave_vector(edge).dot(x));
  Eigen::Matrix3d g;
  g << 1.0, 0.3, -0.2, 0.1, -0.5, 0.4, 0.25, 0.15, 0.6;
  return 1e-3 * (Eigen::Vector3d(0.2, -0.1, 0.3) * edge + g * x);
}

BlockStudyResult run_block_study(const BlockStudy& study, const RpimSettings& settings) {
  const int n = study.nodes_per_edge;
  MeshlessProblem p;
  p.size = Eigen::Vector3d::Constant(study.edge);
  p.cells = {study.cells_per_edge, study.cells_per_edge, study.cells_per_edge};
  p.gauss_order = study.gauss_order;
  p.youngs_modulus = study.youngs_modulus;
  p.poisson_ratio = study.poisson_ratio;
  const double h = study.edge / (n - 1);
  p.mean_spacing = h;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d x(i * h, j * h, k * h);
        const bool boundary = i == 0 || j == 0 || k == 0 || i == n - 1 || j == n - 1 || k == n - 1;
        if (boundary)
          p.constraints.push_back({static_cast<int>(p.nodes.size()),
                                   manufactured_displacement(study.field, study.edge, x)});
        p.nodes.push_back(x);
      }
  const RpimModel model(p, settings);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * model.num_nodes());
  if (study.field == ManufacturedField::plane_wave) {
    const LameParameters m = model.material();
    const double edge = study.edge;
    f = model.body_force([m, edge](const Eigen::Vector3d& x) { return body_force(m, edge, x); });
  }
  const Eigen::VectorXd u = model.solve(f);

  BlockStudyResult r;
  r.nodes = model.num_nodes();
  r.spacing = h;
  double sum = 0;
  for (int i = 0; i < model.num_nodes(); ++i) {
    const Eigen::Vector3d exact = manufactured_displacement(study.field, study.edge, p.nodes[i]);
    const double e = (u.segment<3>(3 * i) - exact).norm();
    r.max_error = std::max(r.max_error, e);
    r.reference = std::max(r.reference, exact.norm());
    sum += e * e;
  }
  r.rms_error = std::sqrt(sum / model.num_nodes());
  return r;
}

}  // namespace softsim::meshless
