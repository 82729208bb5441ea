#include "softsim/io/mesher_config.hpp"

#include "softsim/io/limits.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/io/vtu_writer.hpp"

namespace softsim::io {

namespace {

void read_cuboid(const JsonReader& source, MesherConfig& c) {
  const auto cells = source.get_ints("cells");
  source.require(cells.size() == 3, "cells", "[nx, ny, nz]");
  for (int a = 0; a < 3; ++a) {
    source.require(cells[a] >= 1 && cells[a] <= 400, "cells", "cell counts between 1 and 400");
    c.cuboid.cells[a] = static_cast<int>(cells[a]);
  }
  // The artifact holds each node and tetrahedron three times at its peak: in the mesh, as a
  // JSON value (about 16 bytes a number plus an array per row) and as text.
  const double cell_count = static_cast<double>(cells[0]) * static_cast<double>(cells[1]) * static_cast<double>(cells[2]);
  const double node_count = static_cast<double>(cells[0] + 1) * static_cast<double>(cells[1] + 1) * static_cast<double>(cells[2] + 1);
  require_memory(source, "cells", node_count * kMeshBytesPerNode + 5.0 * cell_count * kMeshBytesPerTet,
                 "the mesh and its artifact");
  const auto size = source.get_doubles("size", 3);
  for (int a = 0; a < 3; ++a) {
    source.require(size[a] > 0, "size", "three positive edge lengths in metres");
    c.cuboid.size[a] = size[a];
  }
  if (source.has("origin")) {
    const auto o = source.get_doubles("origin", 3);
    c.cuboid.origin = Eigen::Vector3d(o[0], o[1], o[2]);
  }
  source.reject_unknown();
  c.source = {{"kind", "cuboid"}, {"cells", cells}, {"size", size}};
}

void read_file(const JsonReader& source, MesherConfig& c) {
  c.from_file = true;
  c.path = source.get_string("path");
  c.file.scale = source.get_positive("scale", 1.0);
  c.file.target_edge = source.has("target_edge") ? source.get_positive("target_edge") : 0.0;
  source.reject_unknown();
  c.source = {{"kind", "file"}, {"path", c.path}, {"scale", c.file.scale}};
}

}  // namespace

MesherConfig read_mesher_config(const JsonReader& cfg) {
  MesherConfig c;
  c.sliver_threshold_deg = cfg.get_positive("sliver_threshold_deg", c.sliver_threshold_deg);
  c.vtu = cfg.get_string("vtu", "");
  c.vtu_format =
      *parse_vtu_format(cfg.get_choice("vtu_format", kVtuFormatNames, vtu_format_name(kDefaultVtuFormat)));
  const JsonReader source = cfg.at("source");
  cfg.reject_unknown();
  if (source.get_choice("kind", {"cuboid", "file"}) == "cuboid")
    read_cuboid(source, c);
  else
    read_file(source, c);
  return c;
}

void check_built_mesh(const nlohmann::json& payload, const std::string& config_path) {
  try {
    mesh_from_json(JsonReader(payload, "the mesh built", "/payload"));
  } catch (const InputError& e) {
    throw InputError(config_path + ": /source: expected a mesh that passes the mesh reader's checks (sizes and origin " +
                     "whose tetrahedra have a positive volume in double precision), got " + e.what());
  }
}

mesh::TetMesh build_mesh(const MesherConfig& c) {
  return c.from_file ? load_mesh_file(c.path, c.file) : mesh::make_cuboid(c.cuboid);
}

nlohmann::json mesher_payload(const mesh::TetMesh& m, const mesh::QualityReport& quality, const nlohmann::json& source) {
  nlohmann::json payload = mesh_to_json(m);
  payload["quality"] = quality_to_json(quality);
  payload["source"] = source;
  return payload;
}

void write_mesher_vtu(const std::string& path, const mesh::TetMesh& m, VtuFormat format) {
  VtuFields fields;
  fields.cell_ints = m.element_tags;
  write_vtu(path, m, fields, format);
}

}  // namespace softsim::io
