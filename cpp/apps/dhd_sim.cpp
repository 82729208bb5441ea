// dhd_sim: the dual-mode hybrid explicit FEM of paper 000 (DHD-FEA). Reads a tet_mesh
// artifact, partitions the elements into linear / TLED / corotational, runs the explicit
// central-difference dynamics or the static equilibrium, and writes a "dhd_result" artifact.
// With --bench: steps per second of four partitions in one run ("dhd_bench").
// Config reference: cpp/apps/dhd_sim.md.
#include <cstdio>
#include <iostream>

#include "common/app.hpp"
#include "common/progress_line.hpp"
#include "softsim/hybrid/dhd_run.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/io/vtu_writer.hpp"

using namespace softsim;

namespace {

io::VtuFields vtu_fields(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds,
                         const std::vector<double>& u, const std::vector<double>& v) {
  io::VtuFields f;
  auto& du = f.point_vectors["displacement"];
  auto& dv = f.point_vectors["velocity"];
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    du.emplace_back(u[3 * i], u[3 * i + 1], u[3 * i + 2]);
    dv.emplace_back(v.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(v[3 * i], v[3 * i + 1], v[3 * i + 2]));
  }
  auto& kind = f.cell_ints["element_kind"];
  for (auto k : kinds) kind.push_back(static_cast<int>(k));
  const auto region = mesh.element_tags.find("region");
  f.cell_ints["region"] = region != mesh.element_tags.end() ? region->second : std::vector<int>(mesh.num_tets(), 0);
  return f;
}

std::string snapshot_path(const std::string& vtu, int step) {
  const std::string stem = vtu.size() > 4 && vtu.substr(vtu.size() - 4) == ".vtu" ? vtu.substr(0, vtu.size() - 4) : vtu;
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%06d.vtu", step);
  return stem + buf;
}

void print_bench(const std::vector<hybrid::BenchRun>& runs) {
  std::printf("%-18s %6s %8s %12s %10s %10s %10s\n", "partition", "r", "threads", "steps/s", "ns/linear", "ns/tled",
              "ns/corot");
  for (const auto& b : runs)
    std::printf("%-18s %6.2f %8d %12.1f %10.2f %10.2f %10.2f\n", b.partition.c_str(), b.linear_fraction, b.threads,
                b.steps_per_second, b.ns_per_element[0], b.ns_per_element[1], b.ns_per_element[2]);
}

}  // namespace

int main(int argc, char** argv) {
  app::AppInfo info;
  info.name = "dhd_sim";
  info.summary = "dual-mode hybrid FEM (linear / TLED / corotational elements), explicit or static (paper 000)";
  info.flags = {"--bench"};
  info.config_help =
      "  {\"mesh\": tet_mesh artifact, \"material\": {\"model\", \"E\", \"nu\", \"density\"}, \"damping\": {\"alpha\"},\n"
      "   \"partition\": {\"kind\": uniform|layers|linear_fraction|tags|sphere|strain, ...},\n"
      "   \"boundary\": {\"fixed\", \"prescribed\", \"forces\", \"gravity\", \"probe\"},\n"
      "   \"solver\": {\"kind\": explicit|static, \"steps\", \"dt\" | \"safety_factor\", \"force_dt\", \"increments\", ...},\n"
      "   \"output\": {\"vtu\", \"vtu_interval\", \"trajectories\", \"trajectory_interval\", \"velocity\"},\n"
      "   \"threads\": 1, \"bench\": {\"steps\", \"threads\", \"linear_fraction\"}}\n"
      "  Full reference: cpp/apps/dhd_sim.md";
  return app::run_app(argc, argv, info, [](app::AppContext& ctx) {
    const io::JsonReader& cfg = ctx.config();
    const std::string mesh_path = ctx.input(hybrid::read_mesh_path(cfg));
    const mesh::TetMesh mesh = io::read_mesh_artifact(mesh_path);
    const hybrid::DhdConfig config = hybrid::read_dhd_config(cfg, mesh);
    if (!config.strain_reference.empty()) ctx.input(config.strain_reference);

    if (ctx.flag("--bench")) {
      const auto runs = hybrid::run_bench(mesh, config);
      print_bench(runs);
      ctx.write(hybrid::kBenchSchema, hybrid::kBenchSchemaVersion, hybrid::bench_payload(mesh, config, runs));
      return;
    }

    const std::vector<fem::ElementKind> kinds = hybrid::make_partition(mesh, config.partition);
    dynamics::SnapshotFn snapshot;
    if (!config.output.vtu.empty() && config.output.vtu_interval > 0)
      snapshot = [&](int step, double, const std::vector<double>& u, const std::vector<double>& v) {
        io::write_vtu(snapshot_path(config.output.vtu, step), mesh, vtu_fields(mesh, kinds, u, v));
      };
    // Steps, simulated time and steps/s on a terminal; quiet otherwise.
    app::ProgressLine progress_line("dhd_sim", config.explicit_solver.steps);
    dynamics::ProgressFn progress;
    if (progress_line.enabled() && !config.static_solver)
      progress = [&](int steps_done, double time) { progress_line.update(steps_done, time); };
    const hybrid::DhdRun run = hybrid::run_dhd(mesh, config, kinds, snapshot, progress);
    if (!config.output.vtu.empty()) {
      const std::vector<double>& u =
          run.explicit_result ? run.explicit_result->displacement : run.static_result->displacement;
      const std::vector<double> v = run.explicit_result ? run.explicit_result->velocity : std::vector<double>();
      io::write_vtu(config.output.vtu, mesh, vtu_fields(mesh, run.kinds, u, v));
    }
    ctx.write(hybrid::kResultSchema, hybrid::kResultSchemaVersion, hybrid::result_payload(mesh, config, run));
    if (run.explicit_result)
      std::cerr << "dhd_sim: " << run.explicit_result->steps << " explicit steps of " << run.step.dt << " s (critical "
                << run.critical.dt << " s), " << run.explicit_result->timing.steps_per_second << " steps/s\n";
    else
      std::cerr << "dhd_sim: static equilibrium in " << config.static_options.increments << " increments\n";
  });
}
