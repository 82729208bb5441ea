#include "softsim/mesh/vtk_cells.hpp"

#include "softsim/io/errors.hpp"

namespace softsim::mesh {

namespace {
// Other writers' names for the region of an element, in order of preference: the breast mesh's
// "materials", and meshio's "gmsh:physical" (a Gmsh mesh converted to VTK).
constexpr const char* kRegionAliases[] = {"materials", "gmsh:physical"};
}  // namespace

TetMesh tets_from_vtk_cells(std::vector<Eigen::Vector3d> points, const VtkCells& cells,
                            const std::map<std::string, std::vector<int>>& cell_tags, const std::string& source) {
  if (points.empty()) throw InputError(source + ": expected at least one point, got none");
  if (cells.types.size() != cells.size())
    throw InputError(source + ": expected as many cell types (" + std::to_string(cells.types.size()) +
                     ") as cells (" + std::to_string(cells.size()) + ")");
  TetMesh mesh;
  mesh.nodes = std::move(points);
  std::map<std::string, std::vector<int>> tags;
  const auto ids = static_cast<std::int64_t>(cells.connectivity.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::int64_t begin = cells.offsets[i], count = cells.offsets[i + 1] - begin;
    if (begin < 0 || count < 0 || cells.offsets[i + 1] > ids)
      throw InputError(source + ": cell " + std::to_string(i) + ": expected non-decreasing offsets within the " +
                       std::to_string(ids) + " point ids of the connectivity, got " +
                       std::to_string(cells.offsets[i + 1]));
    if (cells.types[i] != kVtkTetra) continue;
    if (count != 4)
      throw InputError(source + ": cell " + std::to_string(i) + ": expected 4 points for a VTK_TETRA, got " +
                       std::to_string(count));
    Tet t;
    for (int c = 0; c < 4; ++c) {
      const auto id = cells.connectivity[static_cast<std::size_t>(begin + c)];
      if (id < 0 || id >= static_cast<std::int64_t>(mesh.nodes.size()))
        throw InputError(source + ": cell " + std::to_string(i) + ": expected a point index below " +
                         std::to_string(mesh.nodes.size()) + ", got " + std::to_string(id));
      t[c] = static_cast<int>(id);
    }
    mesh.tets.push_back(t);
    for (const auto& [name, values] : cell_tags)
      if (values.size() == cells.size()) tags[name].push_back(values[i]);
  }
  if (mesh.tets.empty()) throw InputError(source + ": expected at least one VTK_TETRA cell, got none");
  mesh.element_tags = std::move(tags);
  if (!mesh.element_tags.count("region")) {
    mesh.element_tags["region"] = std::vector<int>(mesh.tets.size(), 0);
    for (const char* alias : kRegionAliases)
      if (mesh.element_tags.count(alias)) {
        mesh.element_tags["region"] = mesh.element_tags[alias];
        break;
      }
  }
  drop_unused_nodes(mesh);
  return mesh;
}

}  // namespace softsim::mesh
