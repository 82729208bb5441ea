#include "softsim/mesh/closed_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <Eigen/Geometry>

#include "softsim/io/errors.hpp"

namespace softsim::mesh {

namespace {

double box_distance2(const Eigen::Vector3d& x, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double e = x[k] < lo[k] ? lo[k] - x[k] : (x[k] > hi[k] ? x[k] - hi[k] : 0.0);
    d2 += e * e;
  }
  return d2;
}

double corner_angle(const Eigen::Vector3d& at, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  const Eigen::Vector3d u = p - at, v = q - at;
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

}  // namespace

ClosedSurface::ClosedSurface(TriangleSurface surface, const std::string& source) : source_(source) {
  auto fail = [&](const std::string& what) { throw InputError(source + ": expected " + what); };
  if (surface.triangles.size() < 4) fail("a closed triangle surface (at least 4 triangles), got " +
                                         std::to_string(surface.triangles.size()));
  // Keep the vertices the triangles use, in their order.
  std::vector<int> renumber(surface.vertices.size(), -1);
  for (auto& tri : surface.triangles)
    for (int& v : tri) {
      if (v < 0 || v >= static_cast<int>(surface.vertices.size())) fail("vertex indices in range");
      if (renumber[v] < 0) {
        renumber[v] = static_cast<int>(verts_.size());
        verts_.push_back(surface.vertices[v]);
      }
      v = renumber[v];
    }
  tris_ = std::move(surface.triangles);
  lo_ = hi_ = verts_[0];
  for (const auto& x : verts_) {
    lo_ = lo_.cwiseMin(x);
    hi_ = hi_.cwiseMax(x);
  }
  const double diag = (hi_ - lo_).norm();
  // Closed and consistently oriented: each directed edge once, and its reverse once.
  std::map<std::pair<int, int>, int> directed;
  for (std::size_t t = 0; t < tris_.size(); ++t) {
    const Triangle& tri = tris_[t];
    const Eigen::Vector3d& a = verts_[tri[0]];
    const double twice_area = (verts_[tri[1]] - a).cross(verts_[tri[2]] - a).norm();
    if (!(twice_area > 1e-12 * diag * diag))
      fail("no degenerate triangle, got triangle " + std::to_string(t) + " of zero area");
    for (int k = 0; k < 3; ++k)
      if (!directed.emplace(std::make_pair(tri[k], tri[(k + 1) % 3]), static_cast<int>(3 * t + k)).second)
        fail("a consistently oriented, manifold surface, got edge " + std::to_string(tri[k]) + "-" +
             std::to_string(tri[(k + 1) % 3]) + " twice in one direction (triangle " + std::to_string(t) + ")");
  }
  for (const auto& [edge, where] : directed)
    if (!directed.count({edge.second, edge.first}))
      fail("a closed surface, got the open edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second) +
           " (triangle " + std::to_string(where / 3) + ")");
  for (const Triangle& tri : tris_) volume_ += verts_[tri[0]].dot(verts_[tri[1]].cross(verts_[tri[2]])) / 6.0;
  if (!(std::abs(volume_) > 1e-12 * diag * diag * diag)) fail("a surface enclosing a volume, got volume 0");
  if (volume_ < 0) {  // inward: turn every triangle
    volume_ = -volume_;
    for (Triangle& tri : tris_) std::swap(tri[1], tri[2]);
  }
  // Pseudo-normals (Bærentzen & Aanæs 2005).
  const int nt = static_cast<int>(tris_.size());
  face_normal_.resize(nt);
  vertex_normal_.assign(verts_.size(), Eigen::Vector3d::Zero());
  for (int t = 0; t < nt; ++t) {
    const Triangle& tri = tris_[t];
    const Eigen::Vector3d &a = verts_[tri[0]], &b = verts_[tri[1]], &c = verts_[tri[2]];
    face_normal_[t] = (b - a).cross(c - a).normalized();
    vertex_normal_[tri[0]] += corner_angle(a, b, c) * face_normal_[t];
    vertex_normal_[tri[1]] += corner_angle(b, c, a) * face_normal_[t];
    vertex_normal_[tri[2]] += corner_angle(c, a, b) * face_normal_[t];
  }
  for (auto& n : vertex_normal_) n.normalize();
  std::map<std::pair<int, int>, int> owner;  // directed edge -> triangle
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) owner[{tris_[t][k], tris_[t][(k + 1) % 3]}] = t;
  edge_normal_.resize(nt);
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const int other = owner.at({tris_[t][(k + 1) % 3], tris_[t][k]});
      const Eigen::Vector3d sum = face_normal_[t] + face_normal_[other];
      edge_normal_[t][k] = sum.norm() > 1e-12 ? Eigen::Vector3d(sum.normalized()) : face_normal_[t];
    }
  order_.resize(nt);
  for (int t = 0; t < nt; ++t) order_[t] = t;
  nodes_.reserve(2 * nt);
  build(0, nt);
}

int ClosedSurface::build(int first, int count) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::Vector3d lo = verts_[tris_[order_[first]][0]], hi = lo;
  for (int j = first; j < first + count; ++j)
    for (int v : tris_[order_[j]]) {
      lo = lo.cwiseMin(verts_[v]);
      hi = hi.cwiseMax(verts_[v]);
    }
  nodes_[id].lo = lo;
  nodes_[id].hi = hi;
  nodes_[id].first = first;
  nodes_[id].count = count;
  if (count <= 4) return id;
  // Median split of the centroids along the box's longest side.
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  auto centroid = [&](int t) { return verts_[tris_[t][0]][axis] + verts_[tris_[t][1]][axis] + verts_[tris_[t][2]][axis]; };
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](int a, int b) { return centroid(a) < centroid(b) || (centroid(a) == centroid(b) && a < b); });
  const int left = build(first, half);
  const int right = build(first + half, count - half);
  nodes_[id].left = left;
  nodes_[id].right = right;
  nodes_[id].count = 0;
  return id;
}

// Ericson, Real-Time Collision Detection (2005) §5.1.5, with the feature the point lies on.
double ClosedSurface::nearest_on(int t, const Eigen::Vector3d& p, Eigen::Vector3d& point,
                                 Eigen::Vector3d& pseudo) const {
  const Triangle& tri = tris_[t];
  const Eigen::Vector3d &a = verts_[tri[0]], &b = verts_[tri[1]], &c = verts_[tri[2]];
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) {
    point = a;
    pseudo = vertex_normal_[tri[0]];
  } else {
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    const double vc = d1 * d4 - d3 * d2;
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    const double vb = d5 * d2 - d1 * d6;
    const double va = d3 * d6 - d5 * d4;
    if (d3 >= 0 && d4 <= d3) {
      point = b;
      pseudo = vertex_normal_[tri[1]];
    } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
      point = a + d1 / (d1 - d3) * ab;
      pseudo = edge_normal_[t][0];
    } else if (d6 >= 0 && d5 <= d6) {
      point = c;
      pseudo = vertex_normal_[tri[2]];
    } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
      point = a + d2 / (d2 - d6) * ac;
      pseudo = edge_normal_[t][2];
    } else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
      point = b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
      pseudo = edge_normal_[t][1];
    } else {
      const double denom = 1.0 / (va + vb + vc);
      point = a + ab * (vb * denom) + ac * (vc * denom);
      pseudo = face_normal_[t];
    }
  }
  return (p - point).squaredNorm();
}

double ClosedSurface::signed_distance(const Eigen::Vector3d& x, Eigen::Vector3d& normal) const {
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d point = Eigen::Vector3d::Zero(), pseudo = Eigen::Vector3d::UnitZ();
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (box_distance2(x, node.lo, node.hi) >= best) continue;
    if (node.count > 0) {
      for (int j = node.first; j < node.first + node.count; ++j) {
        Eigen::Vector3d q, n;
        const double d2 = nearest_on(order_[j], x, q, n);
        if (d2 < best) {
          best = d2;
          point = q;
          pseudo = n;
        }
      }
      continue;
    }
    // The nearer child last, so that it is searched first.
    const double dl = box_distance2(x, nodes_[node.left].lo, nodes_[node.left].hi);
    const double dr = box_distance2(x, nodes_[node.right].lo, nodes_[node.right].hi);
    if (dl < dr) {
      stack[top++] = node.right;
      stack[top++] = node.left;
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  const Eigen::Vector3d away = x - point;
  const double distance = std::sqrt(best);
  if (!(distance > 0)) {
    normal = pseudo;
    return 0.0;
  }
  const bool inside = away.dot(pseudo) < 0;
  normal = inside ? Eigen::Vector3d(-away / distance) : Eigen::Vector3d(away / distance);
  return inside ? -distance : distance;
}

double ClosedSurface::winding_number(const Eigen::Vector3d& x) const {
  double total = 0;
  for (const Triangle& tri : tris_) {
    const Eigen::Vector3d a = verts_[tri[0]] - x, b = verts_[tri[1]] - x, c = verts_[tri[2]] - x;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(num, den);
  }
  return total / (4.0 * M_PI);
}

}  // namespace softsim::mesh
