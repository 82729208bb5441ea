#include "softsim/mesh/surface.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>

#include "softsim/io/errors.hpp"

namespace softsim::mesh {

namespace {
// Faces of a positively oriented tet (v0..v3), each listed counter-clockwise from outside.
constexpr int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

struct FaceKey {
  std::array<int, 3> v;
  bool operator==(const FaceKey& o) const { return v == o.v; }
};
struct FaceKeyHash {
  std::size_t operator()(const FaceKey& k) const {
    std::size_t h = static_cast<std::size_t>(k.v[0]);
    h = h * 1000003u ^ static_cast<std::size_t>(k.v[1]);
    h = h * 1000003u ^ static_cast<std::size_t>(k.v[2]);
    return h;
  }
};
struct FaceUse {
  int count = 0;
  Triangle oriented{};
  int tet = -1;
};

std::unordered_map<FaceKey, FaceUse, FaceKeyHash> face_uses(const TetMesh& mesh) {
  std::unordered_map<FaceKey, FaceUse, FaceKeyHash> uses;
  uses.reserve(mesh.tets.size() * 3);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const Tet& t = mesh.tets[e];
    for (const auto& f : kFaces) {
      Triangle tri = {t[f[0]], t[f[1]], t[f[2]]};
      FaceKey key{tri};
      std::sort(key.v.begin(), key.v.end());
      FaceUse& use = uses[key];
      ++use.count;
      use.oriented = tri;
      use.tet = static_cast<int>(e);
    }
  }
  return uses;
}
}  // namespace

std::vector<Triangle> extract_boundary(const TetMesh& mesh, const std::string& source) {
  const auto uses = face_uses(mesh);
  std::vector<std::pair<FaceKey, Triangle>> out;
  for (const auto& [key, use] : uses) {
    if (use.count > 2)
      throw InputError(source + ": face (" + std::to_string(key.v[0]) + ", " +
                       std::to_string(key.v[1]) + ", " + std::to_string(key.v[2]) +
                       "): expected a conforming mesh, got a face shared by " +
                       std::to_string(use.count) + " tetrahedra");
    if (use.count == 1) out.push_back({key, use.oriented});
  }
  // Deterministic order, independent of hashing.
  std::sort(out.begin(), out.end(),
            [](const auto& a, const auto& b) { return a.first.v < b.first.v; });
  std::vector<Triangle> tris;
  tris.reserve(out.size());
  for (const auto& p : out) tris.push_back(p.second);
  return tris;
}

std::vector<int> boundary_nodes(const TetMesh& mesh) {
  std::vector<int> nodes;
  for (const auto& t : mesh.boundary) nodes.insert(nodes.end(), t.begin(), t.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

FaceCensus census(const TetMesh& mesh) {
  FaceCensus c;
  const auto uses = face_uses(mesh);
  std::map<std::pair<int, int>, int> edge_count;
  std::set<int> verts;
  for (const auto& [key, use] : uses) {
    if (use.count == 2) ++c.interior_faces;
    else if (use.count > 2) ++c.overshared_faces;
    else {
      ++c.boundary_faces;
      const Triangle& t = use.oriented;
      for (int i = 0; i < 3; ++i) {
        verts.insert(t[i]);
        const int a = t[i], b = t[(i + 1) % 3];
        ++edge_count[{std::min(a, b), std::max(a, b)}];
      }
      // Outward means the opposite vertex of the owning tet lies behind the face.
      const Tet& tet = mesh.tets[use.tet];
      int opposite = -1;
      for (int v : tet)
        if (v != t[0] && v != t[1] && v != t[2]) opposite = v;
      const Eigen::Vector3d n =
          (mesh.nodes[t[1]] - mesh.nodes[t[0]]).cross(mesh.nodes[t[2]] - mesh.nodes[t[0]]);
      if (n.dot(mesh.nodes[opposite] - mesh.nodes[t[0]]) > 0) ++c.inward_triangles;
    }
  }
  c.surface_vertices = static_cast<int>(verts.size());
  c.surface_edges = static_cast<int>(edge_count.size());
  for (const auto& [e, n] : edge_count)
    if (n != 2) ++c.non_manifold_edges;
  c.euler_characteristic = c.surface_vertices - c.surface_edges + c.boundary_faces;
  return c;
}

}  // namespace softsim::mesh
