#pragma once
// The tetrahedral mesh every solver works on (000 Fig. 4: tetrahedra, surface triangles,
// vertices, linked by indices). Coordinates in metres.
#include <array>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace softsim::mesh {

using Tet = std::array<int, 4>;
using Triangle = std::array<int, 3>;

struct TetMesh {
  std::vector<Eigen::Vector3d> nodes;
  // Positively oriented: det[x1-x0, x2-x0, x3-x0] > 0.
  std::vector<Tet> tets;
  // Boundary triangles, counter-clockwise seen from outside (outward normal).
  std::vector<Triangle> boundary;
  // Named node sets (sorted, unique): "bottom", "top", "sides", "boundary", ...
  std::map<std::string, std::vector<int>> node_sets;
  // Per-element integer tags, each vector of size tets.size(): "layer", "region", "physical".
  std::map<std::string, std::vector<int>> element_tags;

  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_tets() const { return static_cast<int>(tets.size()); }
};

// Signed volume (1/6 det[x1-x0, x2-x0, x3-x0]) of tet `t`.
double signed_volume(const TetMesh& mesh, const Tet& t);
double signed_volume(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                     const Eigen::Vector3d& x2, const Eigen::Vector3d& x3);

// Swaps two nodes of every negatively oriented tet. Throws InputError for a degenerate
// (zero-volume) tet, naming its index: `source` says which file it came from.
void orient_positively(TetMesh& mesh, const std::string& source);

// Axis-aligned bounding box (min, max).
std::pair<Eigen::Vector3d, Eigen::Vector3d> bounding_box(const TetMesh& mesh);

// Scales coordinates (a unit conversion at the edge of the project: mm -> m is 1e-3).
void scale(TetMesh& mesh, double factor);

// Per node: whether some tet uses it.
std::vector<char> nodes_in_tets(const TetMesh& mesh);

// Removes nodes used by no tet and renumbers (imported meshes carry stray vertices).
void drop_unused_nodes(TetMesh& mesh);

}  // namespace softsim::mesh
