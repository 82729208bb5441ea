#include "softsim/fit/playback.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace softsim::fit {

SurfacePlayer::SurfacePlayer(const FitModel& model)
    : basis_(model.frame.basis), nodes_(static_cast<int>(model.nodes.rows())) {
  for (int d = 0; d < 3; ++d) {
    const DirectionModel& dm = model.directions[d];
    Family& fam = families_[d];
    fam.present = dm.present;
    if (!dm.present) continue;
    fam.force_to_loaded = dm.force_to_loaded;
    fam.delta_scale = dm.delta_scale;
    fam.order = 0;
    for (const auto& cm : dm.components) fam.order = std::max(fam.order, cm.parameter_order);
    if (fam.order > kMaxOrder) throw std::invalid_argument("SurfacePlayer: relation-3 order above kMaxOrder");
    fam.fields = Eigen::MatrixXd::Zero(3 * nodes_, fam.order + 1);
    for (int c = 0; c < 3; ++c) {
      const ComponentModel& cm = dm.components[c];
      if (cm.surface.model == SurfaceModel::zero) continue;
      const Eigen::MatrixXd G = surface_design(cm.surface, model.frame, model.nodes) * cm.beta;
      for (int j = 0; j < nodes_; ++j) fam.fields.row(3 * j + c).head(G.cols()) = G.row(j);
    }
    if (model.loaded_node_from_relation1) {
      fam.substitute_row = 3 * model.loaded_node + d;  // 002 §5.1.1: δ_d replaces the surface there
      fam.fields.row(fam.substitute_row).setZero();
    }
  }
}

void SurfacePlayer::play(const Eigen::Vector3d& force, double* out) const {
  Eigen::Map<Eigen::VectorXd> u(out, 3 * nodes_);
  u.setZero();
  double phi[kMaxOrder + 1];
  for (int d = 0; d < 3; ++d) {
    const Family& fam = families_[d];
    if (!fam.present) continue;
    const double delta = fam.force_to_loaded(force[d]);  // 002 eqs. 40–42
    evaluate_basis(basis_, fam.order, fam.delta_scale.to_unit(delta), phi);
    u.noalias() += fam.fields * Eigen::Map<const Eigen::VectorXd>(phi, fam.order + 1);  // 002 eqs. 46, 44
    if (fam.substitute_row >= 0) u[fam.substitute_row] += delta;
  }
}

Eigen::Vector3d SurfacePlayer::loaded_displacement(const Eigen::Vector3d& force) const {
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();
  for (int d = 0; d < 3; ++d)
    if (families_[d].present) delta[d] = families_[d].force_to_loaded(force[d]);
  return delta;
}

Eigen::VectorXd surface_coefficients(const FitModel& model, int direction, int component, double delta) {
  const DirectionModel& dm = model.directions[direction];
  const ComponentModel& cm = dm.components[component];
  Eigen::VectorXd phi(cm.parameter_order + 1);
  evaluate_basis(model.frame.basis, cm.parameter_order, dm.delta_scale.to_unit(delta), phi.data());
  return cm.beta * phi;  // 002 eq. 46
}

Eigen::MatrixXd evaluate_direct(const FitModel& model, const Eigen::Vector3d& force) {
  const int n = static_cast<int>(model.nodes.rows());
  Eigen::MatrixXd u = Eigen::MatrixXd::Zero(n, 3);
  for (int d = 0; d < 3; ++d) {
    const DirectionModel& dm = model.directions[d];
    if (!dm.present) continue;
    const double delta = dm.force_to_loaded(force[d]);
    for (int c = 0; c < 3; ++c) {
      const ComponentModel& cm = dm.components[c];
      if (cm.surface.model == SurfaceModel::zero) continue;
      const Eigen::VectorXd p = surface_coefficients(model, d, c, delta);
      const int order = cm.surface.max_order();
      std::vector<double> px(order + 1), py(order + 1), pz(order + 1);
      for (int j = 0; j < n; ++j) {
        if (model.loaded_node_from_relation1 && j == model.loaded_node && c == d) {
          u(j, c) += delta;  // 002 §5.1.1: eq. 49 substituted at the loaded node
          continue;
        }
        evaluate_basis(model.frame.basis, order, model.frame.x.to_unit(model.nodes(j, 0)), px.data());
        evaluate_basis(model.frame.basis, order, model.frame.y.to_unit(model.nodes(j, 1)), py.data());
        evaluate_basis(model.frame.basis, order, model.frame.z.to_unit(model.nodes(j, 2)), pz.data());
        double value = 0.0;
        for (int k = 0; k < cm.surface.size(); ++k) {
          const auto& t = cm.surface.terms[k];
          value += p[k] * px[t[0]] * py[t[1]] * pz[t[2]];  // 002 eq. 44 (z: the trivariate surface)
        }
        u(j, c) += value;
      }
    }
  }
  return u;
}

}  // namespace softsim::fit
