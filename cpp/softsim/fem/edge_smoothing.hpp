#pragma once
// The isochoric part of the selective smoothed-FEM tetrahedron (ElementKind::smoothed): the
// edge-based smoothed FEM of Nguyen-Thoi, Liu, Lam and Zhang (2009, "ES-FEM-T4") for the
// isochoric energy, the node-based average of nodal_pressure.hpp (as ANP, NS-FEM) for the
// volumetric one — the "selective ES/NS-FEM" of Jiang, Zhang, Liu et al. for nearly
// incompressible solids.
//
// Every edge k of a smoothed element owns a smoothing domain made of a sixth of each smoothed
// element around it, of volume V_k = Σ_{e∋k} ⁰V_e / 6, with the smoothed gradient
//     F_k = Σ_{e∋k} (⁰V_e / 6) F_e / V_k.
// The isochoric energy is Σ_k V_k W_iso(F_k), so corner a of element e receives
//     f_a = (⁰V_e / 6) (Σ_{k ∈ edges(e)} P_iso(F_k)) ∇N_a,
// i.e. each element carries the mean of its six edges' stresses. Under a homogeneous
// deformation every F_k equals F_e and the element is ANP, hence TLED. The edge average softens
// the constant-strain tetrahedron's over-stiff shear response; the nodal volume ratio removes
// most of the volumetric constraints. Cost: one law evaluation per edge (about 1.2 edges per
// tetrahedron in a structured mesh) and the gathers.
#include <array>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/element_kind.hpp"
#include "softsim/fem/tet_geometry.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::fem {

class EdgeSmoothing {
 public:
  // The edges of the elements of kind `smoothed` (none: empty()).
  EdgeSmoothing(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds, const std::vector<TetShape>& shapes);

  bool empty() const { return edge_nodes_.empty(); }
  int num_edges() const { return static_cast<int>(edge_nodes_.size()); }
  // The six edges of a smoothed element (−1 entries for the other kinds).
  const std::array<int, 6>& element_edges(int e) const { return element_edges_[e]; }
  // Edges owned by a node (the edge's lower node): [node_edge_begin(a), node_edge_begin(a + 1)).
  int node_edge_begin(int node) const { return node_edge_begin_[node]; }

  // F_k of edges [begin, end) from the element gradients F (indexed by element).
  void smoothed_gradients(const Eigen::Matrix3d* F, int begin, int end, Eigen::Matrix3d* Fk) const;
  // P_iso(F_k) of edges [begin, end) into P, from the element gradients F (indexed by element).
  void edge_stresses(const Material& m, const Eigen::Matrix3d* F, int begin, int end, Eigen::Matrix3d* P) const;
  // Σ of the six edge stresses of element e, over 6: the element's isochoric stress.
  Eigen::Matrix3d element_stress(int e, const Eigen::Matrix3d* P) const;

  // ---- the clear serial evaluation of the static solver and the tests (all smoothed elements) ----
  // f += the isochoric corner forces at displacement u.
  void add_forces(const Material& m, const double* u, Eigen::VectorXd& f) const;
  // Σ_k V_k W_iso(F_k).
  double energy(const Material& m, const double* u) const;
  // The isochoric energy attributed to element e: Σ_{k ∈ edges(e)} (⁰V_e / 6) W_iso(F_k).
  double element_energy(const Material& m, int e, const double* u) const;
  // Node pairs coupled by an edge's smoothing domain (every pair of nodes of its elements).
  std::vector<std::pair<int, int>> coupled_nodes() const;
  // K += Σ_k V_k (∂F_k/∂u)ᵀ ∂P_iso/∂F (∂F_k/∂u). K's pattern must hold coupled_nodes().
  void add_tangent(const Material& m, const double* u, Eigen::SparseMatrix<double>& K) const;

 private:
  std::vector<Eigen::Matrix3d> element_gradients(const double* u) const;
  // The distinct nodes of edge k's domain and ∂F_k/∂u_b = e_i ⊗ G_b for each.
  void domain_gradients(int k, std::vector<int>& nodes, std::vector<Eigen::Vector3d>& G) const;

  std::vector<mesh::Tet> tets_;
  std::vector<ElementKind> kinds_;
  std::vector<TetShape> shapes_;
  std::vector<std::array<int, 2>> edge_nodes_;     // sorted by lower node
  std::vector<double> edge_volume_;                // V_k
  std::vector<int> edge_begin_;                    // edge → [begin, end) into edge_element_ / edge_weight_
  std::vector<int> edge_element_;                  // the smoothed elements around the edge
  std::vector<double> edge_weight_;                // (⁰V_e / 6) / V_k
  std::vector<std::array<int, 6>> element_edges_;  // per element
  std::vector<int> node_edge_begin_;               // n + 1 offsets
};

}  // namespace softsim::fem
