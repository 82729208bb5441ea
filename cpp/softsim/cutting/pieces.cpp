#include "softsim/cutting/pieces.hpp"

#include <numeric>

namespace softsim::cutting {

namespace {

int root(std::vector<int>& parent, int a) {
  while (parent[a] != a) {
    parent[a] = parent[parent[a]];  // path halving
    a = parent[a];
  }
  return a;
}

}  // namespace

Pieces find_pieces(const mesh::TetMesh& mesh, const std::function<bool(int)>& removed,
                   const std::function<bool(int)>& held) {
  const int n = mesh.num_nodes();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<char> used(n, 0);
  for (int e = 0; e < mesh.num_tets(); ++e) {
    if (removed(e)) continue;
    const auto& t = mesh.tets[e];
    for (int a = 0; a < 4; ++a) used[t[a]] = 1;
    for (int a = 1; a < 4; ++a) {
      const int r0 = root(parent, t[0]), ra = root(parent, t[a]);
      if (r0 != ra) parent[ra] = r0;
    }
  }
  Pieces p;
  p.node_piece.assign(n, -1);
  std::vector<int> label(n, -1);
  for (int a = 0; a < n; ++a) {
    if (!used[a]) continue;
    const int r = root(parent, a);
    if (label[r] < 0) label[r] = p.count++;
    p.node_piece[a] = label[r];
  }
  std::vector<char> anchored(p.count, 0);
  for (int a = 0; a < n; ++a)
    if (p.node_piece[a] >= 0 && held(a)) anchored[p.node_piece[a]] = 1;
  for (int k = 0; k < p.count; ++k)
    if (!anchored[k]) p.loose.push_back(k);
  return p;
}

}  // namespace softsim::cutting
