#include "softsim/cutting/blade.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace softsim::cutting {

std::string sweep_problem(const BladeSweep& s) {
  if (!(s.a0.allFinite() && s.b0.allFinite() && s.a1.allFinite() && s.b1.allFinite()))
    return "a blade position that is not finite";
  const double length = std::max((s.b0 - s.a0).norm(), (s.b1 - s.a1).norm());
  if (!(length > 0)) return "a blade of non-zero length (b differs from a)";
  if ((s.a1 - s.a0).norm() <= 1e-12 * length && (s.b1 - s.b0).norm() <= 1e-12 * length)
    return "a blade that moves (the end position differs from the start)";
  const auto t = swept_triangles(s);
  const double area = 0.5 * ((t[0][1] - t[0][0]).cross(t[0][2] - t[0][0]).norm() +
                             (t[1][1] - t[1][0]).cross(t[1][2] - t[1][0]).norm());
  if (!(area > 1e-12 * length * length)) return "a sweep with an area (the blade moves along its own line)";
  return "";
}

std::array<Triangle, 2> swept_triangles(const BladeSweep& s) {
  return {Triangle{s.a0, s.b0, s.b1}, Triangle{s.a0, s.b1, s.a1}};
}

namespace {

// Whether the projections of the two point sets on `axis` overlap with positive length.
template <std::size_t N, std::size_t M>
bool overlap_on(const Eigen::Vector3d& axis, const std::array<Eigen::Vector3d, N>& p,
                const std::array<Eigen::Vector3d, M>& q, double tol) {
  double pmin = 1e300, pmax = -1e300, qmin = 1e300, qmax = -1e300;
  for (const auto& x : p) {
    const double d = axis.dot(x);
    pmin = std::min(pmin, d);
    pmax = std::max(pmax, d);
  }
  for (const auto& x : q) {
    const double d = axis.dot(x);
    qmin = std::min(qmin, d);
    qmax = std::max(qmax, d);
  }
  return pmax > qmin + tol && qmax > pmin + tol;
}

}  // namespace

bool crosses(const Tetrahedron& tet, const Triangle& tri) {
  // Scale for the tolerances: the sizes involved.
  double size = 0;
  for (int i = 1; i < 4; ++i) size = std::max(size, (tet[i] - tet[0]).norm());
  for (int i = 1; i < 3; ++i) size = std::max(size, (tri[i] - tri[0]).norm());
  const double tol = 1e-12 * size;
  std::array<Eigen::Vector3d, 1 + 4 + 18> axes;  // no allocation: a haptic blade tests every frame
  int count = 0;
  axes[count++] = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (const auto& f : kFace) axes[count++] = (tet[f[1]] - tet[f[0]]).cross(tet[f[2]] - tet[f[0]]);
  static constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d te = tri[(i + 1) % 3] - tri[i];
    for (const auto& e : kEdge) axes[count++] = te.cross(tet[e[1]] - tet[e[0]]);
  }
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d& axis = axes[i];
    const double norm = axis.norm();
    if (!(norm > 1e-12 * size * size)) continue;  // parallel edges: no axis
    if (!overlap_on(axis / norm, tet, tri, tol)) return false;
  }
  return true;
}

namespace {

// Whether the sweep crosses element e in its current geometry (box test first).
bool crossed_now(const mesh::TetMesh& mesh, const double* u, int e, const Eigen::Vector3d& lo,
                 const Eigen::Vector3d& hi, const std::array<Triangle, 2>& triangles) {
  Tetrahedron t;
  Eigen::Vector3d tlo = Eigen::Vector3d::Constant(1e300), thi = Eigen::Vector3d::Constant(-1e300);
  for (int a = 0; a < 4; ++a) {
    const int node = mesh.tets[e][a];
    t[a] = mesh.nodes[node];
    if (u) t[a] += Eigen::Vector3d(u[3 * node], u[3 * node + 1], u[3 * node + 2]);
    tlo = tlo.cwiseMin(t[a]);
    thi = thi.cwiseMax(t[a]);
  }
  if ((tlo.array() > hi.array()).any() || (thi.array() < lo.array()).any()) return false;
  return crosses(t, triangles[0]) || crosses(t, triangles[1]);
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> sweep_box(const BladeSweep& s) {
  return {s.a0.cwiseMin(s.b0).cwiseMin(s.a1).cwiseMin(s.b1), s.a0.cwiseMax(s.b0).cwiseMax(s.a1).cwiseMax(s.b1)};
}

}  // namespace

std::vector<int> elements_crossed(const mesh::TetMesh& mesh, const double* u, const BladeSweep& sweep,
                                  const std::function<bool(int)>& skip) {
  const auto triangles = swept_triangles(sweep);
  const auto [lo, hi] = sweep_box(sweep);
  std::vector<int> out;
  for (int e = 0; e < mesh.num_tets(); ++e)
    if (!(skip && skip(e)) && crossed_now(mesh, u, e, lo, hi, triangles)) out.push_back(e);
  return out;
}

std::vector<int> elements_crossed(const mesh::TetMesh& mesh, const double* u, const BladeSweep& sweep,
                                  const ElementGrid& grid, std::vector<int>& candidates,
                                  const std::function<bool(int)>& skip) {
  const auto triangles = swept_triangles(sweep);
  const auto [lo, hi] = sweep_box(sweep);
  // An element's current box lies within its reference box widened by the largest nodal
  // displacement, so reference boxes overlapping the widened sweep box hold every crossing.
  const Eigen::Vector3d reach = Eigen::Vector3d::Constant(largest_displacement(u, mesh.num_nodes()));
  grid.candidates(lo - reach, hi + reach, candidates);
  std::vector<int> out;
  for (int e : candidates)
    if (!(skip && skip(e)) && crossed_now(mesh, u, e, lo, hi, triangles)) out.push_back(e);
  return out;
}

}  // namespace softsim::cutting
