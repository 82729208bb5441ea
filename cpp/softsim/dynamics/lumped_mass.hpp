#pragma once
// Direct mass lumping (000 §2.2.4, Fig. 7): each tetrahedron gives ρ⁰V/4 to each of its
// four nodes, so the mass matrix is diagonal and the total mass is preserved.
#include <vector>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::dynamics {

std::vector<double> lumped_mass(const mesh::TetMesh& mesh, double density);

}  // namespace softsim::dynamics
