#pragma once
// Geometric node selections for boundary conditions, loads, the probe and trajectories.
#include <vector>

#include <Eigen/Core>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::dynamics {

// The node closest to `point` (the lowest index among equally close nodes).
int nearest_node(const mesh::TetMesh& mesh, const Eigen::Vector3d& point);
// Nodes within `radius` of `center` (ascending).
std::vector<int> nodes_in_sphere(const mesh::TetMesh& mesh, const Eigen::Vector3d& center, double radius);
// Nodes inside the axis-aligned box, bounds inclusive up to 1e-9 of the mesh size (ascending).
std::vector<int> nodes_in_box(const mesh::TetMesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

}  // namespace softsim::dynamics
