#pragma once
// A closed triangle surface as a rigid solid (a meshed instrument, issue 23): the signed
// distance of a point and the outward normal at its nearest surface point, for the kinematic
// contact projection (dynamics::RigidTool).
//
// Inside or outside is decided at the nearest surface point by its angle-weighted pseudo-normal
// (Bærentzen & Aanæs, IEEE TVCG 11 (2005) 243): the face normal on a face, the sum of the two
// face normals on an edge, the sum of the face normals weighted by their corner angles at a
// vertex. For a closed, consistently oriented surface the sign of (x − c)·n at the nearest point
// c is then exact, edges and vertices included, where a face normal alone would give the wrong
// sign near a convex edge seen from inside a concave one. The nearest point is found through a
// bounding-volume hierarchy over the triangles (median splits, boxes), so a query costs about
// log(triangles). winding_number() is the slow, independent inside test (the solid angle the
// surface subtends, Van Oosterom & Strackee 1983) the tests check the sign against.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/mesh/obj_reader.hpp"

namespace softsim::mesh {

class ClosedSurface {
 public:
  // Checks that the surface is closed and consistently oriented (every edge used by exactly two
  // triangles, once in each direction), with no degenerate triangle, and turns it outward (the
  // enclosed volume positive) if it was inward. InputError naming `source` otherwise.
  ClosedSurface(TriangleSurface surface, const std::string& source);

  // Distance of x from the surface, negative inside; `normal`: the unit normal pointing out of
  // the solid at the nearest surface point (from x towards that point when inside, away from it
  // outside; the pseudo-normal when x lies on the surface).
  double signed_distance(const Eigen::Vector3d& x, Eigen::Vector3d& normal) const;
  // Σ solid angles / 4π over the triangles: 1 inside, 0 outside (O(triangles)).
  double winding_number(const Eigen::Vector3d& x) const;

  const Eigen::Vector3d& lower() const { return lo_; }  // bounding box of the vertices
  const Eigen::Vector3d& upper() const { return hi_; }
  double volume() const { return volume_; }
  int num_triangles() const { return static_cast<int>(tris_.size()); }
  int num_vertices() const { return static_cast<int>(verts_.size()); }
  const std::string& source() const { return source_; }

 private:
  struct Node {
    Eigen::Vector3d lo, hi;
    int first = 0, count = 0;  // leaf: triangles order_[first, first + count)
    int left = -1, right = -1;
  };
  int build(int first, int count);
  // Nearest point of triangle t to x: the point and the pseudo-normal of the feature it lies on.
  double nearest_on(int t, const Eigen::Vector3d& x, Eigen::Vector3d& point, Eigen::Vector3d& pseudo) const;

  std::string source_;
  std::vector<Eigen::Vector3d> verts_;
  std::vector<Triangle> tris_;
  std::vector<Eigen::Vector3d> face_normal_;               // per triangle
  std::vector<std::array<Eigen::Vector3d, 3>> edge_normal_;  // per triangle, edge k = corners k, k+1
  std::vector<Eigen::Vector3d> vertex_normal_;             // per vertex (angle-weighted)
  std::vector<int> order_;                                 // triangles in tree order
  std::vector<Node> nodes_;
  Eigen::Vector3d lo_, hi_;
  double volume_ = 0;
};

}  // namespace softsim::mesh
