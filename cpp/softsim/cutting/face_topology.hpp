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

  // A cut opened the face between a and b: neither is the other's neighbour any more.
  void open_face(int a, int b);
  // `copy` (a new node, numbered after every existing one) takes over `node` in `elements`.
  void move_to_copy(int node, int copy, const std::vector<int>& elements);
  // Opened faces whose sides still share all three nodes (the cut's front): kept until a split
  // separates them. take_separated calls face(e, f) for both sides of each one that no longer
  // shares all three (e's local face f) and forgets it.
  void add_pending(int a, int b) { pending_.push_back({a, b}); }
  template <class Face>
  void take_separated(const mesh::TetMesh& mesh, Face face);
  int num_pending() const { return static_cast<int>(pending_.size()); }

 private:
  std::vector<int> neighbour_;                 // 4 per element
  std::vector<int> boundary_triangle_;         // 4 per element
  std::vector<std::vector<int>> elements_at_;  // per node
  std::vector<std::array<int, 2>> pending_;
};

// The local face of `e` holding the three nodes it shares with `other` (−1: they share fewer).
int shared_face(const mesh::TetMesh& mesh, int e, int other);

template <class Face>
void FaceTopology::take_separated(const mesh::TetMesh& mesh, Face face) {
  std::size_t kept = 0;
  for (const auto& p : pending_) {
    const int fa = shared_face(mesh, p[0], p[1]);
    if (fa >= 0) {
      pending_[kept++] = p;
      continue;
    }
    // Each side's face is the one opposite the corner that is not a copy of the other's nodes:
    // found through the reference positions, which a copy shares with its original.
    for (const int e : p) {
      const int other = e == p[0] ? p[1] : p[0];
      for (int f = 0; f < 4; ++f) {
        int matched = 0;
        for (int k = 0; k < 3; ++k) {
          const auto& x = mesh.nodes[mesh.tets[e][kFaceCorners[f][k]]];
          for (int node : mesh.tets[other])
            if (mesh.nodes[node] == x) {
              ++matched;
              break;
            }
        }
        if (matched == 3) {
          face(e, f);
          break;
        }
      }
    }
  }
  pending_.resize(kept);
}

}  // namespace softsim::cutting
