#pragma once
// Scenes shared by the FEM test files: the paper's material and small cuboids of 000's mesher.
#include "softsim/material/elastic.hpp"
#include "softsim/mesh/cuboid.hpp"

namespace softsim::test_scenes {

// 000 §3.1: E = 5000 Pa, ν = 0.35, ρ = 1000 kg/m³.
inline const material::ElasticParameters kPaper{5000.0, 0.35, 1000.0};

inline mesh::TetMesh cuboid(int nx, int ny, int nz, double lx, double ly, double lz) {
  mesh::CuboidSpec s;
  s.cells = {nx, ny, nz};
  s.size = Eigen::Vector3d(lx, ly, lz);
  return mesh::make_cuboid(s);
}

}  // namespace softsim::test_scenes
