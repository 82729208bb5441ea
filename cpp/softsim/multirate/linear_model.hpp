#pragma once
// The linear finite element model of 001 §3, generic over a node graph with a fixed number of
// DOFs per node (1 for the 1-D bar of 001 §6, 3 for a tetrahedral mesh): element stiffness
// matrices assembled into K, a lumped (diagonal) mass, a diagonal damping, and the essential
// boundary conditions condensed out ("the stiffness matrix is condensed so that it does not
// contain the boundary-condition nodes", 001 §3).
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace softsim::multirate {

// One element: the nodes it joins and its stiffness over their DOFs, node-major (the DOFs of
// node a are rows a*dofs_per_node .. a*dofs_per_node + dofs_per_node - 1).
struct LinearElement {
  std::vector<int> nodes;
  Eigen::MatrixXd stiffness;
};

struct LinearModel {
  int dofs_per_node = 1;
  // Node positions (m): used to order the nodes by their distance to the contact node.
  std::vector<Eigen::Vector3d> positions;
  std::vector<LinearElement> elements;
  // Lumped mass of each node (kg), the same for all of its DOFs.
  std::vector<double> nodal_mass;
  // Essential boundary conditions: every DOF of these nodes stays at zero displacement.
  std::vector<int> fixed_nodes;

  int num_nodes() const { return static_cast<int>(positions.size()); }
};

// The sparse LDLT factorisation (fill-reducing AMD ordering) of K in column-major storage.
using StiffnessLdlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

// The model with the fixed nodes condensed out. Free DOF of free node f, component d:
// f * dofs_per_node + d.
struct ReducedSystem {
  int dofs_per_node = 1;
  std::vector<int> model_node;              // free node -> model node
  std::vector<int> free_node;               // model node -> free node, -1 when fixed
  std::vector<Eigen::Vector3d> positions;   // of the free nodes
  std::vector<std::vector<int>> neighbours; // free-node graph (shared elements), sorted
  Eigen::SparseMatrix<double, Eigen::RowMajor> stiffness;  // K over the free DOFs (symmetric)
  Eigen::VectorXd mass;                     // lumped mass per free DOF (kg)
  Eigen::VectorXd damping;                  // diagonal damping per free DOF (N s/m)
  // K factorised once by reduce() for its positive-definiteness check and shared by the later
  // solves with K (natural frequency, contact compliance); empty for a system built otherwise
  // (renumbered). Whatever changes `stiffness` must reset it.
  std::shared_ptr<const StiffnessLdlt> stiffness_ldlt;

  int num_free_nodes() const { return static_cast<int>(model_node.size()); }
  int num_dofs() const { return static_cast<int>(mass.size()); }
};

// Assembles K and the lumped mass, condenses the fixed nodes out, and checks the result:
// symmetric element matrices of the right size, positive mass on every free DOF, and a
// positive definite K (the supports must remove every rigid motion). Damping starts at zero.
// Bad model data -> InputError; a K that is not positive definite -> NumericalError.
ReducedSystem reduce(const LinearModel& model);

// The LDLT of the system's K: the one reduce() made, or a new one (check its info()).
std::shared_ptr<const StiffnessLdlt> factorised_stiffness(const ReducedSystem& system);

// Diagonal damping c_i = alpha * m_i (mass-proportional, so the modes stay uncoupled and the
// explicit stability limit has a closed form).
void set_mass_proportional_damping(ReducedSystem& system, double alpha);

// Lowest undamped natural circular frequency (rad/s) of K phi = omega^2 M phi, by inverse
// iteration with a Rayleigh quotient (converges to relative 1e-12 or throws NumericalError).
double lowest_natural_frequency(const ReducedSystem& system);

// The same system with its free nodes renumbered: new free node k is old free node order[k].
ReducedSystem renumbered(const ReducedSystem& system, const std::vector<int>& order);

}  // namespace softsim::multirate
