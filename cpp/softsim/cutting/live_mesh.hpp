#pragma once
// The mesh of the elements a cut left: the same nodes (numbers, positions, node sets) and the
// elements not removed, in their order, with their kinds. What a method that sets up on the
// cut mesh starts from (a full set-up, a factorisation, a power iteration for the stable step).
#include <functional>
#include <vector>

#include "softsim/fem/element_kind.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::cutting {

struct LiveMesh {
  mesh::TetMesh mesh;
  std::vector<fem::ElementKind> kinds;
};

// `removed(e)`: element e is gone. Element tags and boundary triangles are not carried.
LiveMesh live_mesh(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds,
                   const std::function<bool(int)>& removed);

}  // namespace softsim::cutting
