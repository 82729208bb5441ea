#pragma once
// Cutting by separation along faces (issue 19, the second kind of cut): the mesh opens along
// existing faces near the blade's swept surface by duplicating nodes; no element, no mass and
// no volume is lost.
//
// Which faces: the face shared by two live elements is cut when the segment joining their
// centroids (current geometry) crosses the swept surface. The cut faces are then exactly the
// faces between the elements on one side of the blade and those on the other, within the swept
// area: the swept surface snapped to the mesh faces nearest it, a connected sheet whatever the
// blade's angle to the mesh, and never a face far from the blade.
//
// Which nodes: a node on a cut face splits into as many copies as there are groups of its
// elements joined through uncut faces that contain it (its face-connected fans). The group with
// its lowest-numbered element keeps the node; each other group gets a copy at the same reference
// position. So after a cut no two elements share a node unless a path of uncut faces around
// that node joins them: nothing hangs across the cut by a node or an edge, and where the cut
// ends inside the body (its front) the fans stay joined and the nodes stay whole, so the crack
// simply stops there. A node held by a constraint is not split (its place is prescribed on both
// sides; it is counted).
#include <array>
#include <functional>
#include <vector>

#include "softsim/cutting/blade.hpp"
#include "softsim/cutting/face_topology.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::cutting {

struct NodeSplit {
  int node = 0;               // the node that splits
  int copy = 0;               // the new node: mesh.num_nodes() + k for the k-th split
  std::vector<int> elements;  // the elements that move to the copy, ascending
};

struct SeparationPlan {
  std::vector<std::array<int, 2>> faces;  // cut faces as the pair of elements sharing them (first < second)
  std::vector<NodeSplit> splits;
  int held_nodes_kept = 0;  // nodes of cut faces held by a constraint, not split
  bool empty() const { return faces.empty(); }
};

// The faces the sweep cuts and the node splits that open them, for the mesh in the current
// geometry X + u (u: 3 per node, null for the reference). `near`: the elements to look around
// (the live elements the sweep crosses, elements_crossed); `removed(e)`: element e is gone;
// `held(node)`: a constraint holds it. Changes nothing.
SeparationPlan plan_separation(const mesh::TetMesh& mesh, const double* u, const BladeSweep& sweep,
                               const std::vector<int>& near, const FaceTopology& topology,
                               const std::function<bool(int)>& removed, const std::function<bool(int)>& held);

// What apply_separation changed in the mesh's boundary triangles (their indices stay valid).
struct BoundaryChange {
  std::vector<int> rewritten;  // triangles of moved elements, now on the copies
  int first_new = 0;           // triangles from here on are the sides of opened faces
};

// Applies a plan to the mesh: each copy appended as a node at its original's reference position
// (and to the "boundary" node set if the mesh has one, with its original), the moved elements
// re-pointed to it (their boundary triangles too), and both sides of every cut face that opened
// appended to the boundary triangles, each facing out of its element. The topology follows.
BoundaryChange apply_separation(mesh::TetMesh& mesh, FaceTopology& topology, const SeparationPlan& plan);

// Whether the segment p–q crosses the triangle: its ends on opposite sides of the triangle's
// plane (an end on the plane counts as the side the normal points to) and the crossing point
// inside the closed triangle.
bool segment_crosses(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Triangle& tri);

}  // namespace softsim::cutting
