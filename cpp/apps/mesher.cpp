// mesher: builds or imports a tetrahedral mesh and writes the "tet_mesh" artifact
// (nodes, positively oriented tets, outward boundary, node sets, element tags, quality).
#include <iostream>

#include "common/app.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/io/mesh_files.hpp"
#include "softsim/io/vtu_writer.hpp"
#include "softsim/meshing/gmsh_volume.hpp"
#include "softsim/mesh/cuboid.hpp"
#include "softsim/mesh/quality.hpp"

using namespace softsim;

namespace {

mesh::TetMesh build_mesh(const io::JsonReader& source, nlohmann::json& source_info, app::AppContext& ctx) {
  const std::string kind = source.get_choice("kind", {"cuboid", "file"});
  if (kind == "cuboid") {
    mesh::CuboidSpec spec;
    const auto cells = source.get_ints("cells");
    source.require(cells.size() == 3, "cells", "[nx, ny, nz]");
    for (int a = 0; a < 3; ++a) {
      source.require(cells[a] >= 1 && cells[a] <= 400, "cells", "cell counts between 1 and 400");
      spec.cells[a] = static_cast<int>(cells[a]);
    }
    const auto size = source.get_doubles("size", 3);
    for (int a = 0; a < 3; ++a) {
      source.require(size[a] > 0, "size", "three positive edge lengths in metres");
      spec.size[a] = size[a];
    }
    if (source.has("origin")) {
      const auto o = source.get_doubles("origin", 3);
      spec.origin = Eigen::Vector3d(o[0], o[1], o[2]);
    }
    source.reject_unknown();
    source_info = {{"kind", "cuboid"}, {"cells", cells}, {"size", size}};
    return mesh::make_cuboid(spec);
  }
  io::MeshFileOptions opt;
  const std::string path = ctx.input(source.get_string("path"));
  opt.scale = source.get_positive("scale", 1.0);
  opt.target_edge = source.has("target_edge") ? source.get_positive("target_edge") : 0.0;
  opt.surface_mesher = meshing::volume_from_surface;
  source.reject_unknown();
  source_info = {{"kind", "file"}, {"path", path}, {"scale", opt.scale}};
  return io::load_mesh_file(path, opt);
}

}  // namespace

int main(int argc, char** argv) {
  app::AppInfo info;
  info.name = "mesher";
  info.summary = "build a cuboid of 5-tet cells (000 §2.2.1) or import a mesh; write a tet_mesh artifact";
  info.config_help =
      "  {\"source\": {\"kind\": \"cuboid\", \"cells\": [nx, ny, nz], \"size\": [lx, ly, lz] (m), \"origin\": [x, y, z]}\n"
      "           | {\"kind\": \"file\", \"path\": \"mesh.msh|.vtk|.vtu|.obj|.stl\", \"scale\": to-metres factor, \"target_edge\": h},\n"
      "   \"sliver_threshold_deg\": 5.0,   smallest dihedral angle below which an element is flagged\n"
      "   \"vtu\": \"mesh.vtu\",             optional ParaView file\n"
      "   \"vtu_format\": \"base64\"}         \"ascii\" | \"base64\" (inline binary) | \"raw\" (appended binary)";
  return app::run_app(argc, argv, info, [](app::AppContext& ctx) {
    const io::JsonReader& cfg = ctx.config();
    const double sliver = cfg.get_positive("sliver_threshold_deg", 5.0);
    const std::string vtu = cfg.get_string("vtu", "");
    const io::VtuFormat vtu_format = *io::parse_vtu_format(
        cfg.get_choice("vtu_format", io::kVtuFormatNames, io::vtu_format_name(io::kDefaultVtuFormat)));
    nlohmann::json source_info;
    const io::JsonReader source = cfg.at("source");
    cfg.reject_unknown();
    mesh::TetMesh m = build_mesh(source, source_info, ctx);
    const mesh::QualityReport q = mesh::quality_report(m, sliver);
    nlohmann::json payload = io::mesh_to_json(m);
    payload["quality"] = io::quality_to_json(q);
    payload["source"] = source_info;
    if (!vtu.empty()) {
      io::VtuFields fields;
      fields.cell_ints = m.element_tags;
      io::write_vtu(vtu, m, fields, vtu_format);
    }
    ctx.write(io::kMeshSchema, io::kMeshSchemaVersion, std::move(payload));
    std::cerr << "mesher: " << q.nodes << " nodes, " << q.tets << " tets, " << q.boundary_triangles
              << " boundary triangles, " << q.slivers.size() << " slivers\n";
  });
}
