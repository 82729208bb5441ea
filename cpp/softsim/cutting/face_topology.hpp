#pragma once
// The face structure a cut by separation works on: for every element, the element across each of
// its four faces (face f is the one opposite corner f), and for every node the elements that use
// it. Built once, at the first separating cut (one pass over the faces, sorted); each separation
// then updates it locally: a cut face gets no neighbour on either side, and a node's copy takes
// over the elements moved to it.
#include <array>
#include <vector>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::cutting {

// The corners of face f (opposite corner f) of a positively oriented tetrahedron, counter-clockwise
// seen from outside, so the triangle's normal points out of the element.
inline constexpr int kFaceCorners[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

class FaceTopology {
 public:
  explicit FaceTopology(const mesh::TetMesh& mesh);

  // The element across face f of element e (−1: a boundary face, or one a cut opened).
  int neighbour(int e, int f) const { return neighbour_[4 * static_cast<std::size_t>(e) + f]; }
  // The local face of e shared with element `other` (−1: none).
  int face_towards(int e, int other) const;
  // The elements that use `node`, ascending.
  const std::vector<int>& elements_at(int node) const { return elements_at_[node]; }
  int num_nodes() const { return static_cast<int>(elements_at_.size()); }
  // The mesh's boundary triangle on face f of e (−1: none, or an inner face).
  int boundary_triangle(int e, int f) const { return boundary_triangle_[4 * static_cast<std::size_t>(e) + f]; }
  void set_boundary_triangle(int e, int f, int triangle) { boundary_triangle_[4 * static_cast<std::size_t>(e) + f] = triangle; }

  // A cut opened the face between a and b: neither is the other's neighbour any more. Its two
  // sides stay pending while they share all three nodes (the cut's front), until a split
  // separates them.
  void open_face(int a, int b);
  // `copy` (a new node, numbered after every existing one) takes over `node` in `elements`.
  void move_to_copy(int node, int copy, const std::vector<int>& elements);
  // The sides (element, local face) of the pending faces whose two sides no longer share all
  // three nodes, both sides of each; they are pending no more.
  std::vector<std::array<int, 2>> take_separated(const mesh::TetMesh& mesh);

 private:
  std::vector<int> neighbour_;                 // 4 per element
  std::vector<int> boundary_triangle_;         // 4 per element
  std::vector<std::vector<int>> elements_at_;  // per node
  std::vector<std::array<int, 4>> pending_;    // opened faces still joined: (a, face of a, b, face of b)
};

}  // namespace softsim::cutting
