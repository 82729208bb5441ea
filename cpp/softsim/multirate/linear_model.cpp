#include "softsim/multirate/linear_model.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "softsim/io/errors.hpp"

namespace softsim::multirate {

namespace {

using Triplet = Eigen::Triplet<double>;

void check_element(const LinearModel& model, const LinearElement& e, std::size_t index) {
  const std::string where = "linear model: element " + std::to_string(index);
  if (e.nodes.empty()) throw InputError(where + ": has no nodes");
  const int size = static_cast<int>(e.nodes.size()) * model.dofs_per_node;
  if (e.stiffness.rows() != size || e.stiffness.cols() != size)
    throw InputError(where + ": stiffness is " + std::to_string(e.stiffness.rows()) + "x" +
                     std::to_string(e.stiffness.cols()) + ", expected " + std::to_string(size) + "x" +
                     std::to_string(size));
  for (int n : e.nodes)
    if (n < 0 || n >= model.num_nodes()) throw InputError(where + ": node " + std::to_string(n) + " out of range");
  const double scale = e.stiffness.cwiseAbs().maxCoeff();
  if (!std::isfinite(scale)) throw InputError(where + ": stiffness is not finite");
  if ((e.stiffness - e.stiffness.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale)
    throw InputError(where + ": stiffness is not symmetric");
}

}  // namespace

ReducedSystem reduce(const LinearModel& model) {
  const int dpn = model.dofs_per_node;
  if (dpn < 1 || dpn > 6) throw InputError("linear model: dofs_per_node must be between 1 and 6");
  const int nodes = model.num_nodes();
  if (static_cast<int>(model.nodal_mass.size()) != nodes)
    throw InputError("linear model: one lumped mass per node expected");

  ReducedSystem sys;
  sys.dofs_per_node = dpn;
  sys.free_node.assign(nodes, 0);
  for (int n : model.fixed_nodes) {
    if (n < 0 || n >= nodes) throw InputError("linear model: fixed node " + std::to_string(n) + " out of range");
    sys.free_node[n] = -1;
  }
  for (int n = 0; n < nodes; ++n) {
    if (sys.free_node[n] < 0) continue;
    if (!(model.nodal_mass[n] > 0) || !std::isfinite(model.nodal_mass[n]))
      throw InputError("linear model: node " + std::to_string(n) + " has no positive lumped mass");
    sys.free_node[n] = sys.num_free_nodes();
    sys.model_node.push_back(n);
    sys.positions.push_back(model.positions[n]);
  }
  const int free_nodes = sys.num_free_nodes();
  if (free_nodes == 0) throw InputError("linear model: every node is fixed");
  const int dofs = free_nodes * dpn;

  sys.mass.resize(dofs);
  for (int f = 0; f < free_nodes; ++f) sys.mass.segment(f * dpn, dpn).setConstant(model.nodal_mass[sys.model_node[f]]);
  sys.damping = Eigen::VectorXd::Zero(dofs);

  std::vector<std::set<int>> adjacency(free_nodes);
  std::vector<Triplet> triplets;
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const LinearElement& el = model.elements[e];
    check_element(model, el, e);
    const int en = static_cast<int>(el.nodes.size());
    for (int a = 0; a < en; ++a) {
      const int fa = sys.free_node[el.nodes[a]];
      if (fa < 0) continue;  // condensed out: a fixed node's rows and columns drop (zero displacement)
      for (int b = 0; b < en; ++b) {
        const int fb = sys.free_node[el.nodes[b]];
        if (fb < 0) continue;
        if (fb != fa) adjacency[fa].insert(fb);
        for (int i = 0; i < dpn; ++i)
          for (int j = 0; j < dpn; ++j) {
            const double k = el.stiffness(a * dpn + i, b * dpn + j);
            if (k != 0.0) triplets.emplace_back(fa * dpn + i, fb * dpn + j, k);
          }
      }
    }
  }
  sys.stiffness.resize(dofs, dofs);
  sys.stiffness.setFromTriplets(triplets.begin(), triplets.end());
  sys.stiffness.makeCompressed();
  sys.neighbours.resize(free_nodes);
  for (int f = 0; f < free_nodes; ++f) sys.neighbours[f].assign(adjacency[f].begin(), adjacency[f].end());

  // Positive definiteness: the supports must remove every rigid-body motion.
  std::shared_ptr<const StiffnessLdlt> ldlt = factorised_stiffness(sys);
  if (ldlt->info() != Eigen::Success || (ldlt->vectorD().array() <= 0.0).any())
    throw NumericalError("linear model: the condensed stiffness matrix is not positive definite "
                         "(the fixed nodes do not remove every rigid-body motion)");
  sys.stiffness_ldlt = std::move(ldlt);
  return sys;
}

std::shared_ptr<const StiffnessLdlt> factorised_stiffness(const ReducedSystem& system) {
  if (system.stiffness_ldlt) return system.stiffness_ldlt;
  const Eigen::SparseMatrix<double> k_col = system.stiffness;
  return std::make_shared<StiffnessLdlt>(k_col);
}

void set_mass_proportional_damping(ReducedSystem& system, double alpha) {
  if (!(alpha >= 0) || !std::isfinite(alpha)) throw InputError("damping: alpha must be a finite number >= 0");
  system.damping = alpha * system.mass;
}

double lowest_natural_frequency(const ReducedSystem& system) {
  // Inverse iteration on K x = lambda M x: x <- K^-1 M x converges to the lowest mode at the
  // rate lambda_1 / lambda_2; the Rayleigh quotient converges at its square.
  const Eigen::SparseMatrix<double> k_col = system.stiffness;  // for the Rayleigh quotient
  const std::shared_ptr<const StiffnessLdlt> ldlt = factorised_stiffness(system);
  if (ldlt->info() != Eigen::Success) throw NumericalError("natural frequency: stiffness factorisation failed");
  const Eigen::VectorXd& m = system.mass;
  Eigen::VectorXd x = Eigen::VectorXd::Ones(system.num_dofs());
  double lambda = 0.0;
  for (int it = 0; it < 10000; ++it) {
    Eigen::VectorXd y = ldlt->solve(m.cwiseProduct(x));
    const double next = y.dot(k_col * y) / y.dot(m.cwiseProduct(y));
    y /= std::sqrt(y.dot(m.cwiseProduct(y)));
    x = y;
    if (it > 2 && std::abs(next - lambda) <= 1e-13 * next) return std::sqrt(next);
    lambda = next;
  }
  throw NumericalError("natural frequency: inverse iteration did not converge in 10000 iterations");
}

ReducedSystem renumbered(const ReducedSystem& system, const std::vector<int>& order) {
  const int free_nodes = system.num_free_nodes();
  const int dpn = system.dofs_per_node;
  if (static_cast<int>(order.size()) != free_nodes) throw InputError("renumbering: wrong order size");
  std::vector<int> rank(free_nodes, -1);
  for (int k = 0; k < free_nodes; ++k) {
    const int old = order[k];
    if (old < 0 || old >= free_nodes || rank[old] >= 0) throw InputError("renumbering: order is not a permutation");
    rank[old] = k;
  }
  ReducedSystem out;
  out.dofs_per_node = dpn;
  out.free_node = system.free_node;
  for (int& f : out.free_node)
    if (f >= 0) f = rank[f];
  out.model_node.resize(free_nodes);
  out.positions.resize(free_nodes);
  out.neighbours.resize(free_nodes);
  out.mass.resize(system.num_dofs());
  out.damping.resize(system.num_dofs());
  for (int k = 0; k < free_nodes; ++k) {
    const int old = order[k];
    out.model_node[k] = system.model_node[old];
    out.positions[k] = system.positions[old];
    for (int nb : system.neighbours[old]) out.neighbours[k].push_back(rank[nb]);
    std::sort(out.neighbours[k].begin(), out.neighbours[k].end());
    out.mass.segment(k * dpn, dpn) = system.mass.segment(old * dpn, dpn);
    out.damping.segment(k * dpn, dpn) = system.damping.segment(old * dpn, dpn);
  }
  std::vector<Triplet> triplets;
  triplets.reserve(system.stiffness.nonZeros());
  for (int r = 0; r < system.stiffness.outerSize(); ++r)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(system.stiffness, r); it; ++it) {
      const int i = rank[r / dpn] * dpn + r % dpn;
      const int j = rank[it.col() / dpn] * dpn + it.col() % dpn;
      triplets.emplace_back(i, j, it.value());
    }
  out.stiffness.resize(system.num_dofs(), system.num_dofs());
  out.stiffness.setFromTriplets(triplets.begin(), triplets.end());
  out.stiffness.makeCompressed();
  return out;
}

}  // namespace softsim::multirate
