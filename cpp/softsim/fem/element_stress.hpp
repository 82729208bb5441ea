#pragma once
// Strain and stress of every element for output (the VTU cell data of dhd_sim): the
// Green–Lagrange strain E = ½ (FᵀF − I), the Cauchy stress σ of each element under its own
// constitutive law (constitutive.hpp), and the von Mises equivalent stress. Constant per element
// (linear tetrahedra).
#include <vector>

#include <Eigen/Core>

#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/element_kind.hpp"
#include "softsim/fem/nodal_pressure.hpp"
#include "softsim/fem/tet_geometry.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::fem {

// E = ½ (FᵀF − I): zero under any rigid rotation.
Eigen::Matrix3d green_lagrange_strain(const Eigen::Matrix3d& F);

// The Cauchy (true) stress of an element of `kind` at F, from the element's first Piola–Kirchhoff
// stress P(F) (first_piola):
//   linear        P itself: the small-strain σ = 2μ ε + λ tr(ε) I (000 eq. 10), for which the
//                 linear theory does not tell the reference from the current configuration
//   tled, corot.  σ = J⁻¹ P Fᵀ (J = det F)
//   anp           σ = J⁻¹ P_iso Fᵀ + p̄ I: P_iso is the element's isochoric part and
//                 p̄ cof F its volumetric part (nodal_pressure.hpp), and cof F Fᵀ = J I
// Symmetrised (it is symmetric up to round-off).
Eigen::Matrix3d cauchy_stress(const Material& m, ElementKind kind, const Eigen::Matrix3d& F, double anp_pressure = 0);

// σ_vM = √(3/2 s:s) with the deviator s = σ − tr(σ)/3 I: 0 for a hydrostatic state, |σ₁₁| under
// uniaxial stress. (VTK's "effective stress" of vtkExtractTensorComponents is σ_vM/√3.)
double von_mises_stress(const Eigen::Matrix3d& sigma);

// Every element's E, σ and σ_vM at a displacement field. The geometry, the ANP pressure
// evaluator and the result buffers are set up once, so repeated evaluations (the snapshots of
// an explicit run) reuse them.
class ElementStress {
 public:
  ElementStress(const mesh::TetMesh& mesh, std::vector<ElementKind> kinds, const Material& material);

  // u: 3 values per node.
  void evaluate(const double* u);

  const std::vector<Eigen::Matrix3d>& strain() const { return strain_; }
  const std::vector<Eigen::Matrix3d>& stress() const { return stress_; }
  const std::vector<double>& von_mises() const { return von_mises_; }

 private:
  Material material_;
  std::vector<mesh::Tet> tets_;
  std::vector<ElementKind> kinds_;
  std::vector<TetShape> shapes_;
  NodalPressure pressure_;
  std::vector<double> pbar_;
  std::vector<Eigen::Matrix3d> strain_, stress_;
  std::vector<double> von_mises_;
};

}  // namespace softsim::fem
