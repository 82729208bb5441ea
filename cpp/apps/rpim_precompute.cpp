// rpim_precompute: the RPIM meshless model of 002 §2 on the plate of 002 §4.1 or an organ mesh (§5.3).
//   dataset      (default) solve a force set at the loaded node (plate: node 61), write "rpim_dataset" ("rpim_dataset_set": several, one build)
//   stability    vary q, alpha_c, d_c or the support around the base setting, write "rpim_stability"
//   convergence  refine a block with a manufactured solution, write "rpim_convergence"
#include <iostream>

#include "common/app.hpp"
#include "softsim/meshless/organ_config.hpp"
#include "softsim/meshless/rpim_modes.hpp"

using namespace softsim;

int main(int argc, char** argv) {
  app::AppInfo info;
  info.name = "rpim_precompute";
  info.summary = "RPIM meshless model of 002 (plate or organ mesh): force datasets, stability sweep, convergence study";
  info.modes = meshless::kRpimModes;
  info.config_help =
      "  {\"plate\": {\"size\", \"nodes\", \"youngs_modulus\", \"poisson_ratio\", \"supports\",\n"
      "             \"background_cells\", \"gauss_order\", \"body_force\"},\n"
      "   or \"organ\": {\"mesh\", \"fixed_sets\", \"loaded_set\", \"youngs_modulus\", \"poisson_ratio\",\n"
      "             \"tet_rule\", \"body_force\"} (mode dataset),\n"
      "   \"rpim\": {\"alpha_c\", \"q\", \"d_c\": {\"length\"|\"spacing_factor\"}, \"polynomial\",\n"
      "            \"support\": {\"kind\": \"radius\"|\"nearest\", ...}, \"max_moment_condition\",\n"
      "            \"max_partition_error\"},\n"
      "   \"penalty\": {\"kind\", \"lambda\"}, \"solver\": \"sparse_ldlt\"|\"dense_llt\",\n"
      "   dataset:     \"dataset\": {\"kind\": \"axis_x|axis_y|axis_z|random|check\", ...}\n"
      "                or \"datasets\": {name: {\"kind\", ...}, ...} (one build), \"output\", \"indentation\"\n"
      "   stability:   \"stability\": {\"q\": [...], \"alpha_c\": [...], \"d_c_spacing_factor\": [...], ...}\n"
      "   convergence: \"block\": {...}, \"nodes_per_edge\": [...]}\n"
      "  Full reference: cpp/apps/rpim_precompute.md";
  return app::run_app(argc, argv, info, [](app::AppContext& ctx) {
    if (ctx.mode == "dataset") {
      const std::string mesh = meshless::organ_mesh_path(ctx.config());
      if (!mesh.empty()) ctx.input(mesh);
    }
    const meshless::RpimOutput out = meshless::run_rpim_mode(ctx.mode, ctx.config());
    ctx.provenance.seed = out.seed;
    ctx.write(out.schema, meshless::kRpimSchemaVersion, out.payload);
    std::cerr << "rpim_precompute" << (ctx.mode == "dataset" ? "" : " " + ctx.mode) << ": " << out.summary << "\n";
  });
}
