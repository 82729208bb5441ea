#pragma once
// The blade of a cut: a straight edge from a to b, swept in one cut event from its start
// position (a0, b0) to its end position (a1, b1). The swept surface is the quadrilateral
// a0 b0 b1 a1, taken as the two triangles (a0, b0, b1) and (a0, b1, a1); the elements it
// crosses (in the current, deformed geometry) are the ones a cut by element removal deletes.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/cutting/element_grid.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::cutting {

struct BladeSweep {
  Eigen::Vector3d a0 = Eigen::Vector3d::Zero(), b0 = Eigen::Vector3d::Zero();  // start (m)
  Eigen::Vector3d a1 = Eigen::Vector3d::Zero(), b1 = Eigen::Vector3d::Zero();  // end (m)
};

using Triangle = std::array<Eigen::Vector3d, 3>;
using Tetrahedron = std::array<Eigen::Vector3d, 4>;

// Empty when the sweep is sound; otherwise what is wrong with it (not finite, a blade of zero
// length, a blade that does not move, or a sweep of no area).
std::string sweep_problem(const BladeSweep& sweep);

std::array<Triangle, 2> swept_triangles(const BladeSweep& sweep);

// Whether a tetrahedron and a triangle share interior points, by the separating-axis test
// (both are convex: the triangle's normal, the tetrahedron's four face normals and the cross
// products of their edges). Touching only (a shared face plane, an edge or a vertex) is not a
// crossing, so a blade along a mesh face cuts no element on either side.
bool crosses(const Tetrahedron& tet, const Triangle& tri);

// The elements whose current geometry X + u (u: 3 per node, or null for the reference) the
// sweep crosses, ascending; `skip(e)` true leaves an element out (one removed already). An
// axis-aligned box test first, then crosses().
std::vector<int> elements_crossed(const mesh::TetMesh& mesh, const double* u, const BladeSweep& sweep,
                                  const std::function<bool(int)>& skip = {});
// The same, testing only the elements the grid finds near the sweep (the same result as the
// scan above; `candidates` is scratch reused between calls).
std::vector<int> elements_crossed(const mesh::TetMesh& mesh, const double* u, const BladeSweep& sweep,
                                  const ElementGrid& grid, std::vector<int>& candidates,
                                  const std::function<bool(int)>& skip = {});

}  // namespace softsim::cutting
