#include "softsim/mesh/vtk_legacy_reader.hpp"

#include <cmath>

#include "softsim/io/errors.hpp"
#include "softsim/mesh/text_tokens.hpp"

namespace softsim::mesh {

namespace {
constexpr int kVtkTetra = 10;
}

TetMesh read_vtk_legacy(const std::string& text, const std::string& source) {
  TextTokens tok(text, source);
  const std::string header = tok.rest_of_line();
  if (header.rfind("# vtk DataFile Version", 0) != 0)
    tok.fail("a legacy VTK header \"# vtk DataFile Version\"", header);
  tok.rest_of_line();  // title
  const std::string format = tok.next("ASCII");
  if (format != "ASCII") tok.fail("ASCII (binary legacy VTK is not supported)", format);
  tok.expect("DATASET");
  const std::string kind = tok.next("UNSTRUCTURED_GRID");
  if (kind != "UNSTRUCTURED_GRID") tok.fail("UNSTRUCTURED_GRID", kind);

  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<std::int64_t>> cells;
  std::vector<int> types;
  std::map<std::string, std::vector<int>> cell_scalars;

  while (!tok.at_end()) {
    const std::string keyword = tok.next("a section keyword");
    if (keyword == "POINTS") {
      const auto n = tok.next_count("point count");
      tok.next("a point data type");
      points.resize(static_cast<std::size_t>(n));
      for (auto& p : points)
        for (int c = 0; c < 3; ++c) p[c] = tok.next_double("a coordinate");
    } else if (keyword == "CELLS") {
      const auto a = tok.next_count("cell count");
      const auto b = tok.next_count("cell list size");
      if (tok.peek() == "OFFSETS") {
        // VTK 5.1 layout: a offsets, then b connectivity ids.
        tok.next("OFFSETS");
        tok.next("an offset type");
        std::vector<std::int64_t> offsets(static_cast<std::size_t>(a));
        for (auto& o : offsets) o = tok.next_int("an offset");
        tok.expect("CONNECTIVITY");
        tok.next("a connectivity type");
        std::vector<std::int64_t> conn(static_cast<std::size_t>(b));
        for (auto& c : conn) c = tok.next_int("a point index");
        for (std::size_t i = 0; i + 1 < offsets.size(); ++i) {
          if (offsets[i] < 0 || offsets[i + 1] < offsets[i] || offsets[i + 1] > b)
            tok.fail("non-decreasing offsets within the connectivity", std::to_string(offsets[i + 1]));
          cells.emplace_back(conn.begin() + offsets[i], conn.begin() + offsets[i + 1]);
        }
      } else {
        for (std::int64_t i = 0; i < a; ++i) {
          const auto nn = tok.next_count("a cell's point count");
          std::vector<std::int64_t> ids(static_cast<std::size_t>(nn));
          for (auto& id : ids) id = tok.next_int("a point index");
          cells.push_back(std::move(ids));
        }
      }
    } else if (keyword == "CELL_TYPES") {
      const auto n = tok.next_count("cell type count");
      types.resize(static_cast<std::size_t>(n));
      for (auto& t : types) t = static_cast<int>(tok.next_int("a cell type"));
    } else if (keyword == "CELL_DATA" || keyword == "POINT_DATA") {
      const auto n = tok.next_count("data count");
      const bool cell = keyword == "CELL_DATA";
      while (!tok.at_end() && (tok.peek() == "SCALARS" || tok.peek() == "FIELD")) {
        const std::string what = tok.next("SCALARS");
        if (what == "FIELD") tok.fail("SCALARS (FIELD data is not supported)", what);
        const std::string name = tok.next("a scalar name");
        const std::string type = tok.next("a scalar type");
        std::string after = tok.rest_of_line();  // optional component count
        if (tok.peek() == "LOOKUP_TABLE") {
          tok.next("LOOKUP_TABLE");
          tok.next("a lookup table name");
        }
        std::vector<int> values;
        for (std::int64_t i = 0; i < n; ++i) {
          const double v = tok.next_double("a scalar value");
          values.push_back(static_cast<int>(std::lround(v)));
        }
        const bool integral = type.find("int") != std::string::npos || type == "long" || type == "short";
        if (cell && integral) cell_scalars[name] = std::move(values);
      }
    } else {
      tok.fail("POINTS, CELLS, CELL_TYPES, CELL_DATA or POINT_DATA", keyword);
    }
  }
  if (points.empty()) throw InputError(source + ": expected a POINTS section, got none");
  if (types.size() != cells.size())
    throw InputError(source + ": expected as many CELL_TYPES (" + std::to_string(types.size()) +
                     ") as CELLS (" + std::to_string(cells.size()) + ")");
  TetMesh mesh;
  mesh.nodes = std::move(points);
  std::map<std::string, std::vector<int>> tags;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (types[i] != kVtkTetra) continue;
    if (cells[i].size() != 4)
      throw InputError(source + ": cell " + std::to_string(i) + ": expected 4 points for a VTK_TETRA, got " +
                       std::to_string(cells[i].size()));
    Tet t;
    for (int c = 0; c < 4; ++c) {
      const auto id = cells[i][static_cast<std::size_t>(c)];
      if (id < 0 || id >= static_cast<std::int64_t>(mesh.nodes.size()))
        throw InputError(source + ": cell " + std::to_string(i) + ": expected a point index below " +
                         std::to_string(mesh.nodes.size()) + ", got " + std::to_string(id));
      t[c] = static_cast<int>(id);
    }
    mesh.tets.push_back(t);
    for (const auto& [name, values] : cell_scalars)
      if (values.size() == cells.size()) tags[name].push_back(values[i]);
  }
  if (mesh.tets.empty()) throw InputError(source + ": expected at least one VTK_TETRA cell, got none");
  mesh.element_tags = std::move(tags);
  if (!mesh.element_tags.count("region"))
    mesh.element_tags["region"] = mesh.element_tags.count("materials")
                                      ? mesh.element_tags["materials"]
                                      : std::vector<int>(mesh.tets.size(), 0);
  drop_unused_nodes(mesh);
  return mesh;
}

}  // namespace softsim::mesh
