#pragma once
// The pieces a cut leaves: connected components of the remaining elements (two elements
// are connected when they share a node), and which of them hang free (no node held by a
// constraint). A loose piece keeps moving under the dynamics; it is reported, not removed.
#include <functional>
#include <vector>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::cutting {

struct Pieces {
  int count = 0;
  std::vector<int> node_piece;  // per node: its piece, −1 for a node without elements
  std::vector<int> loose;       // pieces without a constrained node, ascending
};

// `removed(e)`: element e is gone; `held(node)`: a constraint holds the node. One pass of
// union-find over the remaining elements' nodes.
Pieces find_pieces(const mesh::TetMesh& mesh, const std::function<bool(int)>& removed,
                   const std::function<bool(int)>& held);

}  // namespace softsim::cutting
