#include "softsim/mesh/vtk_legacy_reader.hpp"

#include <climits>
#include <cmath>
#include <set>

#include "softsim/io/errors.hpp"
#include "softsim/mesh/text_tokens.hpp"
#include "softsim/mesh/vtk_cells.hpp"

namespace softsim::mesh {

namespace {

// VTK's legacy names of integer data types.
bool integral_type(const std::string& type) {
  static const std::set<std::string> kIntegral = {"bit",   "char",          "signed_char", "unsigned_char",
                                                  "short", "unsigned_short", "int",         "unsigned_int",
                                                  "long",  "unsigned_long",  "vtkIdType",   "vtktypeint64",
                                                  "vtktypeuint64"};
  return kIntegral.count(type) > 0;
}

bool text_type(const std::string& type) { return type == "string" || type == "utf8_string"; }

// `count` values of an array of `type`. Returns them when `keep` (integer arrays only), and
// otherwise checks and skips them. Strings are single tokens (VTK writes their blanks as %20).
std::vector<int> read_values(TextTokens& tok, std::int64_t count, const std::string& type, bool keep) {
  std::vector<int> values;
  for (std::int64_t i = 0; i < count; ++i) {
    if (text_type(type)) {
      tok.next("a string value");
      continue;
    }
    const double v = tok.next_double("a value of type " + type);
    if (!keep) continue;
    if (v != std::round(v) || std::fabs(v) > INT_MAX)
      tok.fail("an integer value of an integer array", std::to_string(v));
    values.push_back(static_cast<int>(v));
  }
  return values;
}

// The optional block vtkDataWriter puts after an array: "METADATA", then "COMPONENT_NAMES" and
// one line per component, and/or "INFORMATION n" and two lines per key, closed by an empty line.
void skip_metadata(TextTokens& tok, std::int64_t components) {
  if (tok.peek() != "METADATA") return;
  tok.next("METADATA");
  tok.rest_of_line();
  while (!tok.exhausted()) {
    const std::string line = tok.rest_of_line();
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) return;
    const std::string word = line.substr(first, line.find_first_of(" \t\r", first) - first);
    std::int64_t lines = 0;
    if (word == "COMPONENT_NAMES") {
      lines = components;
    } else if (word == "INFORMATION") {
      char* end = nullptr;
      const long long keys = std::strtoll(line.c_str() + first + word.size(), &end, 10);
      if (keys < 0) tok.fail("INFORMATION with a key count", line);
      lines = 2 * keys;
    } else {
      tok.fail("COMPONENT_NAMES, INFORMATION or the empty line that ends METADATA", line);
    }
    for (std::int64_t i = 0; i < lines && !tok.exhausted(); ++i) tok.rest_of_line();
  }
}

// After "FIELD": "name k", then k arrays "name components tuples type" and their values, each
// possibly followed by METADATA (how VTK 9 writes every attribute array it has no role for).
// With `tuples` >= 0 each array must have that many tuples; integer one-component arrays go
// into `tags` when given.
void read_field(TextTokens& tok, std::int64_t tuples, std::map<std::string, std::vector<int>>* tags) {
  tok.next("a field name");
  const auto arrays = tok.next_count("an array count");
  for (std::int64_t i = 0; i < arrays; ++i) {
    const std::string name = tok.next("an array name");
    if (name == "NULL_ARRAY") continue;
    const auto components = tok.next_count("a component count");
    const auto n = tok.next_count("a tuple count");
    const std::string type = tok.next("a data type");
    if (tuples >= 0 && n != tuples)
      tok.fail(std::to_string(tuples) + " tuples (the CELL_DATA or POINT_DATA count)", std::to_string(n));
    const bool keep = tags && components == 1 && integral_type(type);
    std::vector<int> values = read_values(tok, components * n, type, keep);
    if (keep) (*tags)[name] = std::move(values);
    skip_metadata(tok, components);
  }
}

// The attribute arrays after CELL_DATA n or POINT_DATA n. Integer one-component arrays go into
// `tags` when given (cell data); everything else is read and dropped.
void read_attributes(TextTokens& tok, std::int64_t n, std::map<std::string, std::vector<int>>* tags) {
  while (!tok.at_end()) {
    const std::string what = tok.peek();
    if (what == "SCALARS") {
      tok.next("SCALARS");
      const std::string name = tok.next("a scalar name");
      const std::string type = tok.next("a scalar type");
      const std::string after = tok.rest_of_line();  // optional component count
      std::int64_t components = 1;
      if (after.find_first_not_of(" \t\r") != std::string::npos) {
        char* end = nullptr;
        components = std::strtoll(after.c_str(), &end, 10);
        if (components < 1 || components > 4) tok.fail("a component count of 1 to 4 after the scalar type", after);
      }
      if (tok.peek() == "LOOKUP_TABLE") {
        tok.next("LOOKUP_TABLE");
        tok.next("a lookup table name");
      }
      const bool keep = tags && components == 1 && integral_type(type);
      std::vector<int> values = read_values(tok, components * n, type, keep);
      if (keep) (*tags)[name] = std::move(values);
      skip_metadata(tok, components);
    } else if (what == "FIELD") {
      tok.next("FIELD");
      read_field(tok, n, tags);
    } else if (what == "VECTORS" || what == "NORMALS" || what == "TENSORS" || what == "TENSORS6") {
      tok.next(what);
      tok.next("an array name");
      const std::string type = tok.next("a data type");
      const std::int64_t components = what == "TENSORS" ? 9 : what == "TENSORS6" ? 6 : 3;
      read_values(tok, components * n, type, false);
      skip_metadata(tok, components);
    } else {
      return;
    }
  }
}

}  // namespace

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
  VtkCells cells;
  std::map<std::string, std::vector<int>> cell_tags;
  std::int64_t cell_data_count = -1;
  int cell_data_line = 0;

  while (!tok.at_end()) {
    const std::string keyword = tok.next("a section keyword");
    if (keyword == "POINTS") {
      const auto n = tok.next_count("point count");
      tok.next("a point data type");
      points.resize(static_cast<std::size_t>(n));
      for (auto& p : points)
        for (int c = 0; c < 3; ++c) p[c] = tok.next_double("a coordinate");
      skip_metadata(tok, 3);
    } else if (keyword == "CELLS") {
      const auto a = tok.next_count("cell count");
      const auto b = tok.next_count("cell list size");
      cells = VtkCells();
      if (tok.peek() == "OFFSETS") {
        // VTK 5.1 layout: a offsets (the first 0, the last b), then b connectivity ids.
        tok.next("OFFSETS");
        tok.next("an offset type");
        if (a < 1) tok.fail("at least one offset", std::to_string(a));
        cells.offsets.resize(static_cast<std::size_t>(a));
        for (auto& o : cells.offsets) o = tok.next_int("an offset");
        tok.expect("CONNECTIVITY");
        tok.next("a connectivity type");
        cells.connectivity.resize(static_cast<std::size_t>(b));
        for (auto& c : cells.connectivity) c = tok.next_int("a point index");
      } else {
        for (std::int64_t i = 0; i < a; ++i) {
          const auto nn = tok.next_count("a cell's point count");
          for (std::int64_t k = 0; k < nn; ++k) cells.connectivity.push_back(tok.next_int("a point index"));
          cells.offsets.push_back(static_cast<std::int64_t>(cells.connectivity.size()));
        }
      }
    } else if (keyword == "CELL_TYPES") {
      const auto n = tok.next_count("cell type count");
      cells.types.resize(static_cast<std::size_t>(n));
      for (auto& t : cells.types) t = tok.next_int32("a cell type");
    } else if (keyword == "CELL_DATA") {
      cell_data_line = tok.line();
      cell_data_count = tok.next_count("data count");
      read_attributes(tok, cell_data_count, &cell_tags);
    } else if (keyword == "POINT_DATA") {
      read_attributes(tok, tok.next_count("data count"), nullptr);
    } else if (keyword == "FIELD") {
      read_field(tok, -1, nullptr);  // data-set field data (e.g. TIME): not per element
    } else {
      tok.fail("POINTS, CELLS, CELL_TYPES, CELL_DATA, POINT_DATA or FIELD", keyword);
    }
  }
  if (cell_data_count >= 0 && static_cast<std::size_t>(cell_data_count) != cells.size())
    throw InputError(source + ": line " + std::to_string(cell_data_line) + ": expected CELL_DATA " +
                     std::to_string(cells.size()) + " (one value per cell), got CELL_DATA " +
                     std::to_string(cell_data_count));
  return tets_from_vtk_cells(std::move(points), cells, cell_tags, source);
}

}  // namespace softsim::mesh
