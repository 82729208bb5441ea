#include "softsim/haptic/contact_surface.hpp"

#include <algorithm>
#include <limits>
#include <set>

#include "softsim/io/errors.hpp"

namespace softsim::haptic {

namespace {

// Barycentric weights of the point of triangle (a, b, c) closest to p (Ericson, Real-Time
// Collision Detection §5.1.5: Voronoi regions of vertices, edges and face).
Eigen::Vector3d closest_weights(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  // d1 = d3 = 0: a and b coincide (a triangle collapsed by an inverted element), vertex a's.
  if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0 && (d4 - d3) + (d5 - d6) > 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  // A triangle flattened to a segment or a point (possible once elements may invert) has no
  // face region: the nearest of its vertices stands in for it.
  if (!(va + vb + vc > 0)) {
    const double da = ap.squaredNorm(), db = bp.squaredNorm(), dc = cp.squaredNorm();
    if (da <= db && da <= dc) return {1, 0, 0};
    return db <= dc ? Eigen::Vector3d(0, 1, 0) : Eigen::Vector3d(0, 0, 1);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

}  // namespace

ContactSurface::ContactSurface(const mesh::TetMesh& mesh) : mesh_(mesh), triangles_(mesh.boundary) {
  if (triangles_.empty()) throw InputError("contact surface: the mesh has no boundary triangles");
  live_.assign(triangles_.size(), 1);
  index_nodes();
}

void ContactSurface::index_nodes() {
  const int n = mesh_.num_nodes();
  node_triangle_begin_.assign(n + 1, 0);
  for (int t = 0; t < num_triangles(); ++t)
    if (live_[t])
      for (int v : triangles_[t]) ++node_triangle_begin_[v + 1];
  for (int i = 0; i < n; ++i) node_triangle_begin_[i + 1] += node_triangle_begin_[i];
  node_triangles_.resize(node_triangle_begin_[n]);
  std::vector<int> fill(node_triangle_begin_.begin(), node_triangle_begin_.end() - 1);
  for (int t = 0; t < num_triangles(); ++t)
    if (live_[t])
      for (int v : triangles_[t]) node_triangles_[fill[v]++] = t;
}

void ContactSurface::follow_separation(const cutting::BoundaryChange& change) {
  for (int t : change.rewritten) triangles_[t] = mesh_.boundary[t];
  // The surface mirrors the mesh's boundary triangle by triangle (a separating scene does not
  // also remove elements, HapticScene): take the ones not taken yet.
  for (int t = std::max(change.first_new, num_triangles()); t < static_cast<int>(mesh_.boundary.size()); ++t) {
    triangles_.push_back(mesh_.boundary[t]);
    live_.push_back(1);
  }
  index_nodes();
}

void ContactSurface::remove_elements(const std::vector<int>& elements, const std::function<bool(int)>& removed) {
  if (elements.empty()) return;
  using Face = std::array<int, 3>;
  auto key = [](Face f) {
    std::sort(f.begin(), f.end());
    return f;
  };
  static constexpr int kOpposite[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  auto face_of = [&](int e, int a) {
    const auto& t = mesh_.tets[e];
    return Face{t[kOpposite[a][0]], t[kOpposite[a][1]], t[kOpposite[a][2]]};
  };
  if (node_tet_begin_.empty()) {  // node -> tetrahedra, once: the neighbours of a face are found locally
    const int n = mesh_.num_nodes();
    node_tet_begin_.assign(n + 1, 0);
    for (const auto& t : mesh_.tets)
      for (int v : t) ++node_tet_begin_[v + 1];
    for (int i = 0; i < n; ++i) node_tet_begin_[i + 1] += node_tet_begin_[i];
    node_tets_.resize(node_tet_begin_[n]);
    std::vector<int> fill(node_tet_begin_.begin(), node_tet_begin_.end() - 1);
    for (int e = 0; e < mesh_.num_tets(); ++e)
      for (int v : mesh_.tets[e]) node_tets_[fill[v]++] = e;
  }
  std::set<Face> cut_faces;
  for (int e : elements)
    for (int a = 0; a < 4; ++a) cut_faces.insert(key(face_of(e, a)));
  // A cut face on the surface leaves it (its live triangle is among those at its first node);
  // any other cut face had a neighbour: if that one is left, its face joins the surface,
  // oriented outward from it (kOpposite keeps the mesh's outward orientation for a positively
  // oriented tetrahedron).
  std::vector<int> leaving;
  std::vector<Face> joining;
  for (const Face& f : cut_faces) {
    int on_surface = -1;
    for (int k = node_triangle_begin_[f[0]]; k < node_triangle_begin_[f[0] + 1] && on_surface < 0; ++k)
      if (key(triangles_[node_triangles_[k]]) == f) on_surface = node_triangles_[k];
    if (on_surface >= 0) {
      leaving.push_back(on_surface);
      continue;
    }
    for (int k = node_tet_begin_[f[0]]; k < node_tet_begin_[f[0] + 1]; ++k) {
      const int e = node_tets_[k];
      if (removed(e)) continue;
      for (int a = 0; a < 4; ++a)
        if (key(face_of(e, a)) == f) joining.push_back(face_of(e, a));
    }
  }
  for (int t : leaving) live_[t] = 0;
  for (const Face& f : joining) {
    triangles_.push_back(f);
    live_.push_back(1);
  }
  index_nodes();
}

Eigen::Vector3d ContactSurface::deformed(int node, const double* u) const {
  return mesh_.nodes[node] + Eigen::Vector3d(u[3 * node], u[3 * node + 1], u[3 * node + 2]);
}

SurfacePoint ContactSurface::at(int triangle, const Eigen::Vector3d& weights, const double* u) const {
  SurfacePoint s;
  s.triangle = triangle;
  s.nodes = triangles_[triangle];
  s.weights = weights;
  const Eigen::Vector3d a = deformed(s.nodes[0], u), b = deformed(s.nodes[1], u), c = deformed(s.nodes[2], u);
  s.position = weights[0] * a + weights[1] * b + weights[2] * c;
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double len = n.norm();
  s.normal = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
  return s;
}

SurfacePoint ContactSurface::closest_on(int triangle, const Eigen::Vector3d& x, const double* u) const {
  const auto& t = triangles_[triangle];
  return at(triangle, closest_weights(x, deformed(t[0], u), deformed(t[1], u), deformed(t[2], u)), u);
}

SurfacePoint ContactSurface::closest(const Eigen::Vector3d& x, const double* u) const {
  SurfacePoint best;
  double best_d = std::numeric_limits<double>::infinity();
  for (int t = 0; t < num_triangles(); ++t) {
    if (!live_[t]) continue;
    const SurfacePoint s = closest_on(t, x, u);
    const double d = (s.position - x).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = s;
    }
  }
  return best;
}

SurfacePoint ContactSurface::closest_near(const Eigen::Vector3d& x, const double* u, const SurfacePoint& from,
                                          int max_walk) const {
  bool unused = false;
  return walk(x, u, from, nullptr, unused, max_walk);
}

SurfacePoint ContactSurface::closest_near(const Eigen::Vector3d& x, const double* u, const SurfacePoint& from,
                                          const std::vector<char>& older, bool& read_older, int max_walk) const {
  read_older = false;
  return walk(x, u, from, &older, read_older, max_walk);
}

SurfacePoint ContactSurface::walk(const Eigen::Vector3d& x, const double* u, const SurfacePoint& from,
                                  const std::vector<char>* older, bool& read_older, int max_walk) const {
  auto note = [&](int t) {
    if (older)
      for (int v : triangles_[t]) read_older = read_older || (*older)[v] != 0;
  };
  note(from.triangle);
  SurfacePoint best = closest_on(from.triangle, x, u);
  double best_d = (best.position - x).squaredNorm();
  for (int move = 0; move < max_walk; ++move) {
    const int current = best.triangle;
    for (int v : triangles_[current])
      for (int k = node_triangle_begin_[v]; k < node_triangle_begin_[v + 1]; ++k) {
        const int t = node_triangles_[k];
        if (t == current) continue;
        note(t);
        const SurfacePoint s = closest_on(t, x, u);
        const double d = (s.position - x).squaredNorm();
        // Strictly closer, so an edge or vertex shared by two triangles keeps its triangle.
        if (d < best_d * (1 - 1e-12)) {
          best_d = d;
          best = s;
        }
      }
    if (best.triangle == current) break;
  }
  return best;
}

}  // namespace softsim::haptic
