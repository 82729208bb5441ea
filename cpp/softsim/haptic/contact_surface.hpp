#pragma once
// Where the probe touches the organ: a point of the boundary surface, held as a triangle and
// barycentric weights, so the spring force spreads over the triangle's three nodes (w_a f on
// node a). As the probe slides, the point follows the closest point of the deformed surface to
// the probe tip, found by a local walk over neighbouring triangles. The weights change
// continuously, also across an edge or a vertex (both triangles give the same weights there),
// so the force has no jump when the contact passes from one node to the next; a contact held
// on the nearest node (001's collision step) would jump by the spring's whole force.
#include <array>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "softsim/cutting/separation.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::haptic {

struct SurfacePoint {
  int triangle = -1;                             // index into the mesh's boundary
  std::array<int, 3> nodes{};                    // its nodes
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  // barycentric, summing to 1
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // Σ w_a x_a in the deformed state (m)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();    // outward unit normal of the deformed triangle
};

class ContactSurface {
 public:
  // The boundary triangles of `mesh` (outward oriented) and which triangles meet at each node.
  // InputError when the mesh has no boundary.
  explicit ContactSurface(const mesh::TetMesh& mesh);

  int num_triangles() const { return static_cast<int>(triangles_.size()); }
  // The closest point of the deformed surface (u: 3 per node) to `x`, over every triangle:
  // where a contact starts.
  SurfacePoint closest(const Eigen::Vector3d& x, const double* u) const;
  // The closest point near `from`: a walk from its triangle over the triangles sharing a node,
  // while a closer one is found (at most `max_walk` moves). Cost independent of the mesh size.
  SurfacePoint closest_near(const Eigen::Vector3d& x, const double* u, const SurfacePoint& from,
                            int max_walk = 64) const;
  // The same walk, telling whether it read a node that `older` (per node) marks as one whose
  // displacement in `u` may be out of date: then the caller brings u up to date and walks again.
  SurfacePoint closest_near(const Eigen::Vector3d& x, const double* u, const SurfacePoint& from,
                            const std::vector<char>& older, bool& read_older, int max_walk = 64) const;
  // The point of `triangle` with barycentric `weights`, in the deformed state.
  SurfacePoint at(int triangle, const Eigen::Vector3d& weights, const double* u) const;

  // A cut removed `elements`: their faces on the surface leave it, and the faces they
  // uncover on the elements left join it, oriented outward. Triangle indices of the faces that
  // stay do not change (a contact on one stays valid); removed triangles are never returned
  // again. Faces are matched through the node → triangle and node → tetrahedron lists (local);
  // the node → triangle lists are then rebuilt (linear in the surface size). `removed(e)`:
  // element e is gone (the ones given here included).
  void remove_elements(const std::vector<int>& elements, const std::function<bool(int)>& removed);
  // A cut separated the mesh along faces (cutting/separation.hpp): the triangles of moved
  // elements now hold node copies, and the sides of the opened faces join the surface. Indices
  // stay valid (a contact on a rewritten triangle follows its element's side).
  void follow_separation(const cutting::BoundaryChange& change);
  bool live(int triangle) const { return live_[triangle] != 0; }
  const std::array<int, 3>& triangle(int t) const { return triangles_[t]; }

 private:
  void index_nodes();
  SurfacePoint closest_on(int triangle, const Eigen::Vector3d& x, const double* u) const;
  SurfacePoint walk(const Eigen::Vector3d& x, const double* u, const SurfacePoint& from,
                    const std::vector<char>* older, bool& read_older, int max_walk) const;
  Eigen::Vector3d deformed(int node, const double* u) const;

  const mesh::TetMesh& mesh_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<char> live_;  // per triangle: still on the surface
  std::vector<int> node_triangle_begin_, node_triangles_;  // CSR: live triangles at each node
  std::vector<int> node_tet_begin_, node_tets_;            // CSR: tetrahedra at each node (built at the first cut)
};

}  // namespace softsim::haptic
