#include "softsim/cutting/face_topology.hpp"

#include <algorithm>
#include <tuple>

namespace softsim::cutting {

FaceTopology::FaceTopology(const mesh::TetMesh& mesh) {
  const int n = mesh.num_tets();
  neighbour_.assign(4 * static_cast<std::size_t>(n), -1);
  elements_at_.assign(mesh.num_nodes(), {});
  // Every face as (sorted corner nodes, element, local face); equal keys are the two sides.
  std::vector<std::tuple<std::array<int, 3>, int, int>> faces;
  faces.reserve(4 * static_cast<std::size_t>(n));
  for (int e = 0; e < n; ++e)
    for (int f = 0; f < 4; ++f) {
      std::array<int, 3> key;
      for (int k = 0; k < 3; ++k) key[k] = mesh.tets[e][kFaceCorners[f][k]];
      std::sort(key.begin(), key.end());
      faces.emplace_back(key, e, f);
    }
  std::sort(faces.begin(), faces.end());
  for (std::size_t i = 0; i + 1 < faces.size(); ++i)
    if (std::get<0>(faces[i]) == std::get<0>(faces[i + 1])) {
      const auto [ka, ea, fa] = faces[i];
      const auto [kb, eb, fb] = faces[i + 1];
      neighbour_[4 * static_cast<std::size_t>(ea) + fa] = eb;
      neighbour_[4 * static_cast<std::size_t>(eb) + fb] = ea;
      ++i;
    }
  for (int e = 0; e < n; ++e)
    for (int a : mesh.tets[e]) elements_at_[a].push_back(e);  // ascending: e grows
  // The boundary triangles on the faces without a neighbour, matched by their sorted nodes.
  boundary_triangle_.assign(4 * static_cast<std::size_t>(n), -1);
  std::vector<std::pair<std::array<int, 3>, int>> triangles;
  for (std::size_t t = 0; t < mesh.boundary.size(); ++t) {
    std::array<int, 3> key = mesh.boundary[t];
    std::sort(key.begin(), key.end());
    triangles.emplace_back(key, static_cast<int>(t));
  }
  std::sort(triangles.begin(), triangles.end());
  for (const auto& [key, e, f] : faces) {
    if (neighbour(e, f) >= 0) continue;
    const auto it = std::lower_bound(triangles.begin(), triangles.end(), std::make_pair(key, -1));
    if (it != triangles.end() && it->first == key) boundary_triangle_[4 * static_cast<std::size_t>(e) + f] = it->second;
  }
}

int FaceTopology::face_towards(int e, int other) const {
  for (int f = 0; f < 4; ++f)
    if (neighbour(e, f) == other) return f;
  return -1;
}

void FaceTopology::open_face(int a, int b) {
  const int fa = face_towards(a, b), fb = face_towards(b, a);
  if (fa < 0 || fb < 0) return;
  neighbour_[4 * static_cast<std::size_t>(a) + fa] = -1;
  neighbour_[4 * static_cast<std::size_t>(b) + fb] = -1;
  pending_.push_back({a, fa, b, fb});
}

void FaceTopology::move_to_copy(int node, int copy, const std::vector<int>& elements) {
  if (copy >= num_nodes()) elements_at_.resize(copy + 1);
  auto& from = elements_at_[node];
  for (int e : elements) from.erase(std::remove(from.begin(), from.end(), e), from.end());
  auto& to = elements_at_[copy];
  to.insert(to.end(), elements.begin(), elements.end());
  std::sort(to.begin(), to.end());
}

std::vector<std::array<int, 2>> FaceTopology::take_separated(const mesh::TetMesh& mesh) {
  const auto nodes = [&](int e, int f) {
    std::array<int, 3> t;
    for (int k = 0; k < 3; ++k) t[k] = mesh.tets[e][kFaceCorners[f][k]];
    std::sort(t.begin(), t.end());
    return t;
  };
  std::vector<std::array<int, 2>> sides;
  std::size_t kept = 0;
  for (const auto& p : pending_) {
    if (nodes(p[0], p[1]) == nodes(p[2], p[3])) {
      pending_[kept++] = p;
      continue;
    }
    sides.push_back({p[0], p[1]});
    sides.push_back({p[2], p[3]});
  }
  pending_.resize(kept);
  return sides;
}

}  // namespace softsim::cutting
