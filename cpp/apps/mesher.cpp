// mesher: builds or imports a tetrahedral mesh and writes the "tet_mesh" artifact
// (nodes, positively oriented tets, outward boundary, node sets, element tags, quality).
#include <iostream>

#include "common/app.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/io/mesher_config.hpp"
#include "softsim/mesh/quality.hpp"
#include "softsim/meshing/gmsh_volume.hpp"

using namespace softsim;

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
    io::MesherConfig config = io::read_mesher_config(ctx.config());
    config.file.surface_mesher = meshing::volume_from_surface;  // .obj/.stl through the Gmsh API
    if (config.from_file) ctx.input(config.path);
    ctx.output(config.vtu, "/vtu");
    const mesh::TetMesh m = io::build_mesh(config);
    const mesh::QualityReport q = mesh::quality_report(m, config.sliver_threshold_deg);
    nlohmann::json payload = io::mesher_payload(m, q, config.source);
    io::check_built_mesh(payload, ctx.config_path);
    if (!config.vtu.empty()) io::write_mesher_vtu(config.vtu, m, config.vtu_format);
    ctx.write(io::kMeshSchema, io::kMeshSchemaVersion, std::move(payload));
    std::cerr << "mesher: " << q.nodes << " nodes, " << q.tets << " tets, " << q.boundary_triangles
              << " boundary triangles, " << q.slivers.size() << " slivers\n";
  });
}
