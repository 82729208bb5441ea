#include "softsim/mesh/cuboid.hpp"

#include <algorithm>
#include <stdexcept>

#include "softsim/mesh/surface.hpp"

namespace softsim::mesh {

namespace {
// Local corner numbering of a cell: corner (dx, dy, dz) -> dx + 2 dy + 4 dz.
constexpr int corner(int dx, int dy, int dz) { return dx + 2 * dy + 4 * dz; }

// Split "a": the central tet joins the corners with even dx+dy+dz; each odd corner cuts off
// a corner tet with its three (even) neighbours. Split "b" is the mirror image (odd centre).
// Both are listed with the cut-off corner first; orientation is fixed afterwards.
const std::array<Tet, 5> kSplitA = {{
    {corner(0, 0, 0), corner(1, 1, 0), corner(1, 0, 1), corner(0, 1, 1)},
    {corner(1, 0, 0), corner(0, 0, 0), corner(1, 1, 0), corner(1, 0, 1)},
    {corner(0, 1, 0), corner(0, 0, 0), corner(1, 1, 0), corner(0, 1, 1)},
    {corner(0, 0, 1), corner(0, 0, 0), corner(1, 0, 1), corner(0, 1, 1)},
    {corner(1, 1, 1), corner(1, 1, 0), corner(1, 0, 1), corner(0, 1, 1)},
}};
const std::array<Tet, 5> kSplitB = {{
    {corner(1, 0, 0), corner(0, 1, 0), corner(0, 0, 1), corner(1, 1, 1)},
    {corner(0, 0, 0), corner(1, 0, 0), corner(0, 1, 0), corner(0, 0, 1)},
    {corner(1, 1, 0), corner(1, 0, 0), corner(0, 1, 0), corner(1, 1, 1)},
    {corner(1, 0, 1), corner(1, 0, 0), corner(0, 0, 1), corner(1, 1, 1)},
    {corner(0, 1, 1), corner(0, 1, 0), corner(0, 0, 1), corner(1, 1, 1)},
}};
}  // namespace

TetMesh make_cuboid(const CuboidSpec& spec) {
  const int nx = spec.cells[0], ny = spec.cells[1], nz = spec.cells[2];
  if (nx < 1 || ny < 1 || nz < 1) throw std::invalid_argument("cuboid needs at least one cell per axis");
  TetMesh mesh;
  const auto node_id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  mesh.nodes.resize(static_cast<std::size_t>((nx + 1) * (ny + 1) * (nz + 1)));
  const Eigen::Vector3d h(spec.size.x() / nx, spec.size.y() / ny, spec.size.z() / nz);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        mesh.nodes[node_id(i, j, k)] = spec.origin + Eigen::Vector3d(i * h.x(), j * h.y(), k * h.z());

  std::vector<int> layer, region;
  mesh.tets.reserve(static_cast<std::size_t>(5 * nx * ny * nz));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const auto& split = ((i + j + k) % 2 == 0) ? kSplitA : kSplitB;
        for (const Tet& local : split) {
          Tet t;
          for (int c = 0; c < 4; ++c) {
            const int lc = local[c];
            t[c] = node_id(i + (lc & 1), j + ((lc >> 1) & 1), k + ((lc >> 2) & 1));
          }
          if (signed_volume(mesh, t) < 0) std::swap(t[1], t[2]);
          mesh.tets.push_back(t);
          layer.push_back(k);
          region.push_back(0);
        }
      }
  mesh.element_tags["layer"] = std::move(layer);
  mesh.element_tags["region"] = std::move(region);

  auto& bottom = mesh.node_sets["bottom"];
  auto& top = mesh.node_sets["top"];
  auto& xmin = mesh.node_sets["x_min"];
  auto& xmax = mesh.node_sets["x_max"];
  auto& ymin = mesh.node_sets["y_min"];
  auto& ymax = mesh.node_sets["y_max"];
  auto& sides = mesh.node_sets["sides"];
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        const int id = node_id(i, j, k);
        if (k == 0) bottom.push_back(id);
        if (k == nz) top.push_back(id);
        if (i == 0) xmin.push_back(id);
        if (i == nx) xmax.push_back(id);
        if (j == 0) ymin.push_back(id);
        if (j == ny) ymax.push_back(id);
        if (i == 0 || i == nx || j == 0 || j == ny) sides.push_back(id);
      }
  mesh.boundary = extract_boundary(mesh, "cuboid");
  mesh.node_sets["boundary"] = boundary_nodes(mesh);
  return mesh;
}

}  // namespace softsim::mesh
