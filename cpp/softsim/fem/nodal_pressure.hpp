#pragma once
// The average nodal pressure (ANP) tetrahedron (Bonet & Burton 1998; Joldes et al. 2009).
//
// A mesh of constant-strain tetrahedra has five to six elements per node; enforcing J ≈ 1 in
// every element as ν → 0.5 asks for more constraints than the three degrees of freedom per node
// can meet, and the mesh locks. The ANP element keeps the isochoric part W_iso(F) of the
// neo-Hookean energy per element and evaluates the volumetric part U(J) = κ/2 (J − 1)² at the
// nodes, with the nodal volume ratio
//     J_a = v_a / V_a,   V_a = Σ_{e∋a} ⁰V_e / 4,   v_a = Σ_{e∋a} ⁰V_e J_e / 4
// (only ANP and smoothed elements count). The energy Σ_e ⁰V_e W_iso(F_e) + Σ_a V_a U(J_a) gives the element
// forces ⁰V_e (P_iso(F_e) + p̄_e cof F_e) ∇N_a, where p̄_e is the mean of the nodal pressures
// p_a = U'(J_a) = κ (J_a − 1) of its corners: one volumetric constraint per node instead of one
// per element, which removes most of the volumetric locking but not the constant-strain element's
// own stiffness (results/validation/incompressible_summary.md; the smoothed kind, edge_smoothing.hpp,
// also smooths the isochoric part).
// Under a homogeneous deformation every J_a equals J_e and the element is plain TLED.
//
// This file holds a clear (serial) evaluation used by the static solver's assembly and by the
// tests; the explicit engine has its own vectorised path (element_set.hpp). Both build on the
// node ↔ element weights of nodal_volumes.hpp.
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "softsim/fem/element_kind.hpp"
#include "softsim/fem/nodal_volumes.hpp"
#include "softsim/fem/tet_geometry.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::fem {

// cof F = J F⁻ᵀ = ∂J/∂F, and its directional derivative along dF.
Eigen::Matrix3d cofactor(const Eigen::Matrix3d& F);
Eigen::Matrix3d cofactor_increment(const Eigen::Matrix3d& F, const Eigen::Matrix3d& dF);

class NodalPressure {
 public:
  // `kappa`: the volumetric modulus κ of U (Material::volumetric_modulus).
  NodalPressure(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds, const std::vector<TetShape>& shapes,
                double kappa);

  bool empty() const { return empty_; }
  const NodalVolumes& volumes() const { return nodal_; }

  // J_a for every node (1 at nodes without ANP elements).
  void nodal_volume_ratios(const double* u, std::vector<double>& J) const;
  // p̄_e for every element (0 for other kinds).
  void element_pressures(const double* u, std::vector<double>& pbar) const;
  // f += the volumetric corner forces ⁰V_e p̄_e cof F_e ∇N_a of every ANP element.
  void add_forces(const double* u, Eigen::VectorXd& f) const;
  // Σ_a V_a U(J_a).
  double energy(const double* u) const;

  // Node pairs (b, c) coupled by the volumetric tangent: both corners of ANP elements around a
  // common node (a wider stencil than the elements' own).
  std::vector<std::pair<int, int>> coupled_nodes() const;
  // K += ∂(volumetric forces)/∂u = Σ_a V_a κ g_a g_aᵀ + Σ_e ⁰V_e p̄_e ∂(cof F_e ∇N)/∂u, with
  // g_a = ∂J_a/∂u. K's pattern must hold coupled_nodes().
  void add_tangent(const double* u, Eigen::SparseMatrix<double>& K) const;

 private:
  // F_e of every ANP element at u (the other entries are not set): each is formed once per call
  // and serves both J_e and cof F_e.
  std::vector<Eigen::Matrix3d> anp_gradients(const double* u) const;
  void nodal_volume_ratios(const std::vector<Eigen::Matrix3d>& F, std::vector<double>& J) const;
  void element_pressures(const std::vector<double>& J, std::vector<double>& pbar) const;

  std::vector<mesh::Tet> tets_;
  std::vector<ElementKind> kinds_;
  std::vector<TetShape> shapes_;
  double kappa_ = 0;
  NodalVolumes nodal_;
  bool empty_ = true;
};

}  // namespace softsim::fem
