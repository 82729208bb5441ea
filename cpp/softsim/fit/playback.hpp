#pragma once
// The real-time path: surface displacement of every node for a force, from a fitted model.
//
// The chain force -> δ (relation 1) -> surface coefficients (relation 3) -> nodal displacement
// (relation 2) is linear in the basis values φ_m(sδ) once the nodes are fixed, so the player
// precomputes, per load direction, the nodal fields G = Ψ β (Ψ: surface basis at the nodes) and a
// playback is, per direction, one polynomial, K + 1 basis values and one matrix–vector product.
// The player allocates only in its constructor.
#include <array>

#include <Eigen/Dense>

#include "softsim/fit/model.hpp"

namespace softsim::fit {

class SurfacePlayer {
 public:
  explicit SurfacePlayer(const FitModel& model);

  int node_count() const { return nodes_; }
  // Writes 3 * node_count() values, node-major (ux, uy, uz of node 0, node 1, ...), in m.
  // Directions the model does not contain contribute nothing. No allocation.
  void play(const Eigen::Vector3d& force, double* out) const;
  // The loaded-node displacements δ_x, δ_y, δ_z of relation 1 (0 for absent directions).
  Eigen::Vector3d loaded_displacement(const Eigen::Vector3d& force) const;

 private:
  struct Family {
    bool present = false;
    Polynomial1D force_to_loaded;
    AffineScale delta_scale;
    int order = 0;           // highest relation-3 order over the components
    Eigen::MatrixXd fields;  // 3n × (order + 1); row 3 j + c
    int substitute_row = -1; // row that takes δ_d itself (FitModel::loaded_node_from_relation1)
  };
  std::array<Family, 3> families_;
  Basis basis_ = Basis::legendre;
  int nodes_ = 0;
};

// The same model evaluated relation by relation (002 eqs. 40–46, 44) at every node, allocating:
// the reference the player is checked against. Returns nodes × 3 (m).
Eigen::MatrixXd evaluate_direct(const FitModel& model, const Eigen::Vector3d& force);

// Surface coefficients p of one (direction, component) for a loaded-node displacement δ
// (002 eq. 46).
Eigen::VectorXd surface_coefficients(const FitModel& model, int direction, int component, double delta);

}  // namespace softsim::fit
