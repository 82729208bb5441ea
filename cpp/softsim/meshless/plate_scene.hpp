#pragma once
// The soft-tissue plate of 002 §4.1 (Fig. 4): 48 × 48 × 6 mm, 11 × 11 × 3 nodes (4.8 mm in
// plane, layers at z = 0, 3, 6 mm), E = 0.32 MPa, ν = 0.49, 64 background cells of
// 6 × 6 × 6 mm, all forces on node 61, the centre of the top face. SI throughout.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/meshless/penalty.hpp"

namespace softsim::meshless {

// "Four edges are fixed" (002 §4.1, red edges in Fig. 4) admits several readings; §5.1.1
// later blames "fixed constraints on corner nodes (1, 11, 111, 121)".
enum class PlateSupports {
  side_faces,             // every node of the four lateral faces x = 0, x = L, y = 0, y = L
  bottom_edges,           // the nodes on the four edges of the bottom face z = 0
  vertical_corner_edges,  // the four vertical edges x, y ∈ {0, L}: the corner nodes of every layer
};
std::string supports_name(PlateSupports s);

struct PlateScene {
  Eigen::Vector3d size{0.048, 0.048, 0.006};  // m
  std::array<int, 3> nodes{11, 11, 3};         // per axis
  double youngs_modulus = 0.32e6;              // Pa
  double poisson_ratio = 0.49;
  PlateSupports supports = PlateSupports::vertical_corner_edges;
  std::array<int, 3> background_cells{8, 8, 1};
  int gauss_order = 4;                         // Gauss points per direction per cell
  Eigen::Vector3d body_force = Eigen::Vector3d::Zero();  // N/m³, added to every load case
};

// Node (i, j, k) at (i hx, j hy, k hz) has index i + nx (j + ny k); the top layer is k = nz-1.
int plate_node_index(const PlateScene& s, int i, int j, int k);
std::vector<Eigen::Vector3d> plate_nodes(const PlateScene& s);
// Top-layer nodes in the paper's numbering N = x/hx + nx y/hy + 1 (N - 1 = i + nx j).
std::vector<int> plate_top_nodes(const PlateScene& s);
// The paper number of the centre of the top face (61 for 11 × 11); needs odd nx and ny.
int plate_loaded_node_number(const PlateScene& s);
int plate_loaded_node_index(const PlateScene& s);
std::vector<int> plate_fixed_nodes(const PlateScene& s);
std::vector<NodeConstraint> plate_constraints(const PlateScene& s);
// (volume / node count)^(1/3): the length that spacing-relative parameters multiply.
double plate_mean_spacing(const PlateScene& s);

}  // namespace softsim::meshless
