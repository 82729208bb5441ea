#include "softsim/fem/linear_rows.hpp"

#include <algorithm>

#include "softsim/fem/element_response.hpp"
#include "softsim/fem/tet_geometry.hpp"

namespace softsim::fem {

LinearStiffnessRows::LinearStiffnessRows(const mesh::TetMesh& mesh, const std::vector<ElementKind>& kinds,
                                         const Material& material) {
  const int n = mesh.num_nodes();
  // Row pattern: every node paired with itself and each node it shares a linear element with.
  std::vector<std::vector<int>> columns(n);
  for (int e = 0; e < mesh.num_tets(); ++e) {
    if (kinds[e] != ElementKind::linear) continue;
    for (int a : mesh.tets[e])
      for (int b : mesh.tets[e]) columns[a].push_back(b);
  }
  row_begin_.assign(n + 1, 0);
  for (int a = 0; a < n; ++a) {
    auto& c = columns[a];
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    row_begin_[a + 1] = row_begin_[a] + static_cast<int>(c.size());
  }
  if (row_begin_[n] == 0) return;  // no linear element: nothing to store
  neighbour_.resize(row_begin_[n]);
  for (int a = 0; a < n; ++a)
    for (std::size_t j = 0; j < columns[a].size(); ++j) neighbour_[row_begin_[a] + j] = 3 * columns[a][j];
  block_.assign(9 * static_cast<std::size_t>(row_begin_[n] + 1), 0.0);

  // Element blocks Kₑ (the linear element's 12 × 12 stiffness, the same function the static
  // solver assembles) added into their rows.
  const Corners zero{};
  for (int e = 0; e < mesh.num_tets(); ++e) {
    if (kinds[e] != ElementKind::linear) continue;
    const ElementMatrix K = element_tangent(material, ElementKind::linear, tet_shape(mesh, e), zero);
    const auto& t = mesh.tets[e];
    for (int a = 0; a < 4; ++a) {
      const int* first = neighbour_.data() + row_begin_[t[a]];
      const int* last = neighbour_.data() + row_begin_[t[a] + 1];
      for (int b = 0; b < 4; ++b) {
        const std::size_t p = std::lower_bound(first, last, 3 * t[b]) - neighbour_.data();
        double* block = block_.data() + 9 * p;
        for (int col = 0; col < 3; ++col)
          for (int row = 0; row < 3; ++row) block[3 * col + row] += K(3 * a + row, 3 * b + col);
      }
    }
  }
}

}  // namespace softsim::fem
