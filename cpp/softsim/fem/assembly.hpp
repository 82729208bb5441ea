#pragma once
// Global assembly for the implicit (static) solver: the internal force vector Σₑ Fₑ
// (000 eq. 27) and the sparse consistent tangent K(u) = ∂F/∂u, from the reference element
// functions, plus the nodal volumetric part of ANP and smoothed elements (nodal_pressure.hpp)
// and the edge-smoothed isochoric part of smoothed elements (edge_smoothing.hpp). Serial; the
// sparsity pattern and the element → value map are built once.
#include <vector>

#include <Eigen/Sparse>

#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/edge_smoothing.hpp"
#include "softsim/fem/element_kind.hpp"
#include "softsim/fem/nodal_pressure.hpp"
#include "softsim/fem/tet_geometry.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::fem {

class Assembler {
 public:
  Assembler(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds, const Material& material);

  int num_dofs() const { return 3 * num_nodes_; }
  // f = Σ over elements of the corner forces at displacement u (3 n values).
  void internal_forces(const double* u, Eigen::VectorXd& f) const;
  // Values of the tangent at u written into K (pattern fixed at construction).
  void tangent(const double* u, Eigen::SparseMatrix<double>& K) const;
  // A matrix with the tangent's pattern (values zero).
  Eigen::SparseMatrix<double> pattern() const { return pattern_; }
  double strain_energy(const double* u) const;
  // Smallest det F over the elements and the element where it occurs.
  double min_volume_ratio(const double* u, int* element = nullptr) const;

  const std::vector<TetShape>& shapes() const { return shapes_; }

 private:
  int num_nodes_;
  std::vector<mesh::Tet> tets_;
  std::vector<ElementKind> kinds_;
  Material material_;
  std::vector<TetShape> shapes_;
  NodalPressure nodal_pressure_;
  EdgeSmoothing edge_smoothing_;  // the isochoric part of smoothed elements
  Eigen::SparseMatrix<double> pattern_;
  std::vector<int> value_index_;  // 144 per element: position in pattern_.valuePtr()
};

}  // namespace softsim::fem
