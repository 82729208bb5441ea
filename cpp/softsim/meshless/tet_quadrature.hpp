#pragma once
// Background integration over tetrahedra: an organ's own tetrahedral mesh carries the Gauss
// points of the RPIM weak form (002 §2.3 integrates over background cells; on a curved organ
// the tetrahedra are the cells that fill the domain exactly). As with the plate's box cells,
// the tetrahedra only carry quadrature: the shape functions ignore them.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "softsim/meshless/background_cells.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::meshless {

// Symmetric rules on a tetrahedron, exact for polynomials up to the given degree:
//   1 point  (centroid)                         degree 1
//   4 points (a = (5 + 3√5)/20, b = (5 − √5)/20) degree 2, positive weights 1/4
//   5 points (Keast: centroid −4/5, 9/20 at (1/2, 1/6, 1/6, 1/6)) degree 3, one negative weight
struct TetRule {
  std::vector<std::array<double, 4>> barycentric;
  std::vector<double> weights;  // sum 1 (fractions of the volume)
  int degree = 0;
};
// Throws std::invalid_argument for a count other than 1, 4 or 5.
TetRule tet_rule(int points);
bool is_tet_rule_size(int points);

// Every tetrahedron of `mesh` with `rule`; points ordered tet by tet, weights in m³ (their sum is
// the mesh volume).
QuadraturePoints tet_quadrature(const mesh::TetMesh& mesh, const TetRule& rule);

}  // namespace softsim::meshless
