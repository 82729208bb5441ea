#pragma once
// An organ as an RPIM problem domain (002 §5.3, Figs. 18–21: "the surface of the liver as a
// problem domain scattered with nodes whose displacements can be computed by the meshless
// method"): the field nodes are the nodes of a tetrahedral organ mesh, the background
// integration runs over its tetrahedra, penalty supports hold named node sets, and the forces
// act on one surface node. Datasets report every surface node (the paper's 1986 on its liver).
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/mesh/tet_mesh.hpp"
#include "softsim/meshless/scene_run.hpp"

namespace softsim::meshless {

struct OrganScene {
  std::string mesh_path;                            // a tet_mesh artifact (mesher, dhd_node_sets)
  std::vector<std::string> fixed_sets{"fixed"};     // node sets held at zero by penalty
  std::string loaded_set = "push";                  // a node set holding exactly one surface node,
  std::optional<Eigen::Vector3d> loaded_point;      // or: the surface node nearest this point (m)
  double youngs_modulus = 0.32e6;                   // Pa (002 §4.1)
  double poisson_ratio = 0.49;
  int tet_rule = 4;                                 // Gauss points per tetrahedron: 1, 4 or 5
  Eigen::Vector3d body_force = Eigen::Vector3d::Zero();  // N/m³, added to every load case
};

// (volume / nodes)^(1/3) of the mesh.
double organ_mean_spacing(const mesh::TetMesh& mesh);

// The scene's nodes, Gauss points (tet_quadrature), material and supports, and which nodes it
// reports and loads. organ_layout throws ConfigInputError (naming the config member under
// /organ) for a set the mesh lacks, a mesh without surface, a loaded set that is not one surface
// node, or a loaded node that is also fixed; call it before organ_problem.
MeshlessProblem organ_problem(const OrganScene& scene, const mesh::TetMesh& mesh);
SceneLayout organ_layout(const OrganScene& scene, const mesh::TetMesh& mesh);

}  // namespace softsim::meshless
