#pragma once
// The benchmarks' scene: 000's paper cuboid (17 × 17 × 10 cells of 1 cm, 14 450 tetrahedra) and
// its material (000 §3.1), built once per program.
#include "softsim/material/elastic.hpp"
#include "softsim/mesh/cuboid.hpp"

namespace softsim::bench {

inline const mesh::TetMesh& paper_mesh() {
  static const mesh::TetMesh m = [] {
    mesh::CuboidSpec s;
    s.cells = {17, 17, 10};
    s.size = Eigen::Vector3d(0.17, 0.17, 0.10);
    return mesh::make_cuboid(s);
  }();
  return m;
}

inline const material::ElasticParameters kPaper{5000.0, 0.35, 1000.0};  // 000 §3.1

}  // namespace softsim::bench
