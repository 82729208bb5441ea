#include "softsim/meshless/plate_scene.hpp"

#include <cmath>
#include <stdexcept>

namespace softsim::meshless {

std::string supports_name(PlateSupports s) {
  switch (s) {
    case PlateSupports::side_faces: return "side_faces";
    case PlateSupports::bottom_edges: return "bottom_edges";
    case PlateSupports::vertical_corner_edges: return "vertical_corner_edges";
  }
  return "?";
}

int plate_node_index(const PlateScene& s, int i, int j, int k) {
  return i + s.nodes[0] * (j + s.nodes[1] * k);
}

std::vector<Eigen::Vector3d> plate_nodes(const PlateScene& s) {
  for (int a = 0; a < 3; ++a)
    if (s.nodes[a] < 2) throw std::invalid_argument("plate_nodes: need at least 2 nodes per axis");
  std::vector<Eigen::Vector3d> x;
  x.reserve(static_cast<std::size_t>(s.nodes[0]) * s.nodes[1] * s.nodes[2]);
  for (int k = 0; k < s.nodes[2]; ++k)
    for (int j = 0; j < s.nodes[1]; ++j)
      for (int i = 0; i < s.nodes[0]; ++i)
        x.emplace_back(s.size.x() * i / (s.nodes[0] - 1), s.size.y() * j / (s.nodes[1] - 1),
                       s.size.z() * k / (s.nodes[2] - 1));
  return x;
}

std::vector<int> plate_top_nodes(const PlateScene& s) {
  std::vector<int> top;
  for (int j = 0; j < s.nodes[1]; ++j)
    for (int i = 0; i < s.nodes[0]; ++i) top.push_back(plate_node_index(s, i, j, s.nodes[2] - 1));
  return top;
}

int plate_loaded_node_number(const PlateScene& s) {
  if (s.nodes[0] % 2 == 0 || s.nodes[1] % 2 == 0)
    throw std::invalid_argument("plate: the loaded centre node needs odd node counts in x and y");
  return (s.nodes[0] - 1) / 2 + s.nodes[0] * ((s.nodes[1] - 1) / 2) + 1;
}

int plate_loaded_node_index(const PlateScene& s) {
  return plate_node_index(s, (s.nodes[0] - 1) / 2, (s.nodes[1] - 1) / 2, s.nodes[2] - 1);
}

std::vector<int> plate_fixed_nodes(const PlateScene& s) {
  const int nx = s.nodes[0], ny = s.nodes[1], nz = s.nodes[2];
  std::vector<int> fixed;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const bool x_edge = i == 0 || i == nx - 1, y_edge = j == 0 || j == ny - 1;
        bool f = false;
        switch (s.supports) {
          case PlateSupports::side_faces: f = x_edge || y_edge; break;
          case PlateSupports::bottom_edges: f = k == 0 && (x_edge || y_edge); break;
          case PlateSupports::vertical_corner_edges: f = x_edge && y_edge; break;
        }
        if (f) fixed.push_back(plate_node_index(s, i, j, k));
      }
  return fixed;
}

std::vector<NodeConstraint> plate_constraints(const PlateScene& s) {
  std::vector<NodeConstraint> c;
  for (int n : plate_fixed_nodes(s)) c.push_back({n, Eigen::Vector3d::Zero()});
  return c;
}

double plate_mean_spacing(const PlateScene& s) {
  const double count = static_cast<double>(s.nodes[0]) * s.nodes[1] * s.nodes[2];
  return std::cbrt(s.size.prod() / count);
}

}  // namespace softsim::meshless
