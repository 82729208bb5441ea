#include "softsim/cutting/separation.hpp"

#include <algorithm>

namespace softsim::cutting {

namespace {

Eigen::Vector3d centroid(const mesh::TetMesh& mesh, const double* u, int e) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int node : mesh.tets[e]) {
    c += mesh.nodes[node];
    if (u) c += Eigen::Vector3d(u[3 * node], u[3 * node + 1], u[3 * node + 2]);
  }
  return 0.25 * c;
}

int find_root(std::vector<int>& parent, int a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

}  // namespace

bool segment_crosses(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Triangle& tri) {
  // The ends on opposite sides of the triangle's plane, a point on the plane counting as the
  // positive side (a blade through a centroid, as on a regular mesh, still gives each face one
  // answer whichever way it is tested), and the crossing point inside the closed triangle.
  const Eigen::Vector3d e1 = tri[1] - tri[0], e2 = tri[2] - tri[0];
  const Eigen::Vector3d n = e1.cross(e2);
  const double dp = n.dot(p - tri[0]), dq = n.dot(q - tri[0]);
  if ((dp >= 0) == (dq >= 0)) return false;
  const Eigen::Vector3d x = p + dp / (dp - dq) * (q - p);
  // Barycentric coordinates of x in the triangle.
  const Eigen::Vector3d r = x - tri[0];
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), r1 = r.dot(e1), r2 = r.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0)) return false;
  const double beta = (d22 * r1 - d12 * r2) / det, gamma = (d11 * r2 - d12 * r1) / det;
  return beta >= 0 && gamma >= 0 && beta + gamma <= 1;
}

SeparationPlan plan_separation(const mesh::TetMesh& mesh, const double* u, const BladeSweep& sweep,
                               const std::vector<int>& near, const FaceTopology& topology,
                               const std::function<bool(int)>& removed, const std::function<bool(int)>& held) {
  SeparationPlan plan;
  const auto triangles = swept_triangles(sweep);
  for (int a : near) {
    if (removed(a)) continue;
    const Eigen::Vector3d ca = centroid(mesh, u, a);
    for (int f = 0; f < 4; ++f) {
      const int b = topology.neighbour(a, f);
      if (b < 0 || removed(b)) continue;
      const Eigen::Vector3d cb = centroid(mesh, u, b);
      if (segment_crosses(ca, cb, triangles[0]) || segment_crosses(ca, cb, triangles[1]))
        plan.faces.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(plan.faces.begin(), plan.faces.end());
  plan.faces.erase(std::unique(plan.faces.begin(), plan.faces.end()), plan.faces.end());
  const auto is_cut = [&](int a, int b) {
    return std::binary_search(plan.faces.begin(), plan.faces.end(), std::array<int, 2>{std::min(a, b), std::max(a, b)});
  };
  // The nodes of the cut faces, ascending.
  std::vector<int> nodes;
  for (const auto& [a, b] : plan.faces)
    for (int node : mesh.tets[a])
      if (std::find(mesh.tets[b].begin(), mesh.tets[b].end(), node) != mesh.tets[b].end()) nodes.push_back(node);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  int next_copy = mesh.num_nodes();
  std::vector<int> fan, parent;
  for (int node : nodes) {
    fan.clear();
    for (int e : topology.elements_at(node))
      if (!removed(e)) fan.push_back(e);  // ascending
    parent.resize(fan.size());
    for (std::size_t i = 0; i < fan.size(); ++i) parent[i] = static_cast<int>(i);
    const auto index = [&](int e) {
      return static_cast<int>(std::lower_bound(fan.begin(), fan.end(), e) - fan.begin());
    };
    // Join the elements around the node through its uncut faces (the three faces of e that
    // contain the node: those opposite its other corners).
    for (std::size_t i = 0; i < fan.size(); ++i) {
      const int e = fan[i];
      for (int f = 0; f < 4; ++f) {
        if (mesh.tets[e][f] == node) continue;
        const int b = topology.neighbour(e, f);
        if (b < 0 || removed(b) || is_cut(e, b)) continue;
        const int ri = find_root(parent, static_cast<int>(i)), rb = find_root(parent, index(b));
        if (ri != rb) parent[std::max(ri, rb)] = std::min(ri, rb);  // the lowest element's group is the root
      }
    }
    // Groups other than the first (the one holding fan[0]) become copies, in the order of their
    // lowest element.
    std::vector<int> group_of(fan.size(), -1);
    std::vector<NodeSplit> splits;
    for (std::size_t i = 0; i < fan.size(); ++i) {
      const int r = find_root(parent, static_cast<int>(i));
      if (r == 0) continue;
      if (group_of[r] < 0) {
        group_of[r] = static_cast<int>(splits.size());
        splits.push_back(NodeSplit{node, 0, {}});
      }
      splits[group_of[r]].elements.push_back(fan[i]);
    }
    if (splits.empty()) continue;
    if (held(node)) {
      ++plan.held_nodes_kept;
      continue;
    }
    for (auto& s : splits) {
      s.copy = next_copy++;
      plan.splits.push_back(std::move(s));
    }
  }
  return plan;
}

BoundaryChange apply_separation(mesh::TetMesh& mesh, FaceTopology& topology, const SeparationPlan& plan) {
  BoundaryChange change;
  const auto face_triangle = [&](int e, int f) {
    mesh::Triangle t;
    for (int k = 0; k < 3; ++k) t[k] = mesh.tets[e][kFaceCorners[f][k]];
    return t;
  };
  auto boundary_set = mesh.node_sets.find("boundary");
  for (const NodeSplit& s : plan.splits) {
    mesh.nodes.push_back(mesh.nodes[s.node]);
    for (int e : s.elements)
      for (int& corner : mesh.tets[e])
        if (corner == s.node) corner = s.copy;
    topology.move_to_copy(s.node, s.copy, s.elements);
    for (int e : s.elements)
      for (int f = 0; f < 4; ++f) {
        const int t = topology.boundary_triangle(e, f);
        if (t < 0 || mesh.tets[e][f] == s.copy) continue;  // the face opposite the copy does not hold it
        mesh.boundary[t] = face_triangle(e, f);
        change.rewritten.push_back(t);
      }
    if (boundary_set != mesh.node_sets.end()) {
      auto& set = boundary_set->second;
      for (int node : {s.node, s.copy})
        if (!std::binary_search(set.begin(), set.end(), node)) set.insert(std::lower_bound(set.begin(), set.end(), node), node);
    }
  }
  // A cut face opens in the topology at once; its two sides join the boundary once they no
  // longer share all three nodes (a face whose nodes all lie on the cut's front waits for a
  // later cut to split one of them).
  for (const auto& [a, b] : plan.faces) topology.open_face(a, b);
  change.first_new = static_cast<int>(mesh.boundary.size());
  for (const auto& [e, f] : topology.take_separated(mesh)) {
    topology.set_boundary_triangle(e, f, static_cast<int>(mesh.boundary.size()));
    mesh.boundary.push_back(face_triangle(e, f));
  }
  std::sort(change.rewritten.begin(), change.rewritten.end());
  change.rewritten.erase(std::unique(change.rewritten.begin(), change.rewritten.end()), change.rewritten.end());
  return change;
}

}  // namespace softsim::cutting
