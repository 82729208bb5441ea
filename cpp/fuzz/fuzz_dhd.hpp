#pragma once
// dhd_sim's body (cpp/apps/dhd_sim.cpp) for the fuzz targets, with bounded work: at most 4
// explicit steps or 2 static increments, one thread, no VTU (a path of the fuzzer's choosing is
// not written). `mesh_path`: the mesh artifact to read instead of the config's "mesh" (whose
// string read_dhd_config still reads; a name of the fuzzer's choosing is not looked up), or "" for
// the config's own.
#include <algorithm>
#include <string>

#include "fuzz_app.hpp"
#include "softsim/hybrid/dhd_run.hpp"
#include "softsim/hybrid/dhd_vtu.hpp"

namespace fuzz {

inline void dhd_body(softsim::app::AppContext& ctx, const std::string& mesh_path) {
  using namespace softsim;
  const io::JsonReader& cfg = ctx.config();
  const mesh::TetMesh mesh = io::read_mesh_artifact(ctx.input(mesh_path.empty() ? hybrid::read_mesh_path(cfg) : mesh_path));
  hybrid::DhdConfig config = hybrid::read_dhd_config(cfg, mesh);
  if (!config.strain_reference.empty()) ctx.input(config.strain_reference);
  ctx.output(config.output.vtu, "/output/vtu");
  config.explicit_solver.steps = std::min(config.explicit_solver.steps, 4);
  config.explicit_solver.energy_interval = std::min(config.explicit_solver.energy_interval, 2);
  config.static_options.increments = std::min(config.static_options.increments, 2);
  config.static_options.max_iterations = std::min(config.static_options.max_iterations, 4);
  config.threads = 1;
  config.output.vtu.clear();
  config.output.vtu_interval = 0;
  const hybrid::DhdRun run = hybrid::run_dhd_writing_vtu(mesh, config, {});
  ctx.write(hybrid::kResultSchema, hybrid::kResultSchemaVersion, hybrid::result_payload(mesh, config, run));
}

// A 2 x 2 x 2-cell cuboid of 2 cm written once as a tet_mesh artifact by mesher's body.
inline const std::string& cuboid_artifact() {
  static const std::string path = [] {
    const std::string out = scratch("cuboid.json");
    const nlohmann::json config = {{"source", {{"kind", "cuboid"}, {"cells", {2, 2, 2}}, {"size", {0.02, 0.02, 0.02}}}}};
    const std::string cfg = config.dump();
    const std::string cfg_path = write_scratch("cuboid-config.json", cfg.data(), cfg.size());
    std::string a0 = "mesher", a1 = "--config", a3 = "--out";
    std::string a2 = cfg_path, a4 = out;
    char* argv[] = {a0.data(), a1.data(), a2.data(), a3.data(), a4.data(), nullptr};
    softsim::app::AppInfo info;
    info.name = "mesher";
    if (softsim::app::run_app(5, argv, info, mesher_body) != 0) std::abort();
    return out;
  }();
  return path;
}

}  // namespace fuzz
