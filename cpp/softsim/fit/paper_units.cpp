#include "softsim/fit/paper_units.hpp"

namespace softsim::fit {

namespace {
constexpr double kMillimetre = 1000.0;  // millimetres per metre
}

Eigen::VectorXd force_relation_in_mm(const DirectionModel& direction) {
  const Polynomial1D& p = direction.force_to_loaded;
  const Eigen::MatrixXd T = basis_to_monomial(p.basis, p.scale, p.order(), 0.0, 1.0);
  return kMillimetre * (T * p.coefficients);
}

PaperSurface surface_in_mm(const FitModel& model, int direction, int component) {
  const DirectionModel& dm = model.directions[direction];
  const ComponentModel& cm = dm.components[component];
  PaperSurface out;
  const int order = cm.surface.max_order();
  const double x0 = model.nodes.col(0).minCoeff();
  const double y0 = model.nodes.col(1).minCoeff();
  // Basis function i of sx as monomials of x[mm] from the corner: Tx(a, i).
  const Eigen::MatrixXd Tx = basis_to_monomial(model.frame.basis, model.frame.x, order, x0, kMillimetre);
  const Eigen::MatrixXd Ty = basis_to_monomial(model.frame.basis, model.frame.y, order, y0, kMillimetre);
  const double z0 = model.nodes.col(2).minCoeff();
  const Eigen::MatrixXd Tz = basis_to_monomial(model.frame.basis, model.frame.z, order, z0, kMillimetre);
  const Eigen::MatrixXd Td =
      basis_to_monomial(model.frame.basis, dm.delta_scale, cm.parameter_order, 0.0, kMillimetre);
  // The monomials a surface of this family spans, in the paper's order (1, x.., y..).
  for (const auto& t : cm.surface.terms) out.powers.push_back(t);
  const int K = cm.parameter_order + 1;
  out.beta = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(out.powers.size()), K);
  // beta_mm(a, b, c; q) = 1000 Σ_k Σ_m Tx(a, i_k) Ty(b, j_k) Tz(c, l_k) β(k, m) Td(q, m).
  const Eigen::MatrixXd beta_delta = cm.beta * Td.transpose();  // terms × K: coefficients of δ_mm^q
  for (std::size_t t = 0; t < out.powers.size(); ++t) {
    const int a = out.powers[t][0], b = out.powers[t][1], c = out.powers[t][2];
    for (int k = 0; k < cm.surface.size(); ++k) {
      const int i = cm.surface.terms[k][0], j = cm.surface.terms[k][1], l = cm.surface.terms[k][2];
      const double w = Tx(a, i) * Ty(b, j) * Tz(c, l);
      if (w != 0.0) out.beta.row(static_cast<Eigen::Index>(t)) += kMillimetre * w * beta_delta.row(k);
    }
  }
  return out;
}

}  // namespace softsim::fit
