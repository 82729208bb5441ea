// dhd_sim: the dual-mode hybrid explicit FEM of paper 000 (DHD-FEA). Reads a tet_mesh
// artifact, partitions the elements into kinds (fem::kElementKinds), runs the explicit
// central-difference dynamics or the static equilibrium, and writes a "dhd_result" artifact.
// With --bench: steps per second of four partitions in one run ("dhd_bench").
// Config reference: cpp/apps/dhd_sim.md.
#include <cstdio>
#include <iostream>

#include "common/app.hpp"
#include "common/progress_line.hpp"
#include "softsim/hybrid/cut_bench.hpp"
#include "softsim/hybrid/dhd_vtu.hpp"
#include "softsim/io/mesh_artifact.hpp"

using namespace softsim;

namespace {

// "linear / tled / corotational / anp".
std::string kinds_in_words() {
  std::string out;
  for (const fem::ElementKindInfo& info : fem::kElementKinds) out += (out.empty() ? "" : " / ") + std::string(info.name);
  return out;
}

// One ns-per-element column per element kind (fem::kElementKinds).
void print_bench(const std::vector<hybrid::BenchRun>& runs) {
  std::printf("%-18s %6s %8s %12s", "partition", "r", "threads", "steps/s");
  for (const fem::ElementKindInfo& info : fem::kElementKinds)
    std::printf(" %*s", 10, (std::string("ns/") + info.name).c_str());
  std::printf("\n");
  for (const auto& b : runs) {
    std::printf("%-18s %6.2f %8d %12.1f", b.partition.c_str(), b.linear_fraction, b.threads, b.steps_per_second);
    for (int k = 0; k < fem::kNumElementKinds; ++k) std::printf(" %10.2f", b.ns_per_element[k]);
    std::printf("\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  app::AppInfo info;
  info.name = "dhd_sim";
  info.summary = "dual-mode hybrid FEM (" + kinds_in_words() + " elements), explicit or static (paper 000)";
  info.flags = {"--bench", "--cut-bench"};
  info.config_help =
      "  {\"mesh\": tet_mesh artifact, \"material\": {\"model\", \"E\", \"nu\", \"density\" | mooney_rivlin: \"C10\", \"C01\", \"K\", \"density\" | ogden: \"mu\", \"alpha\", \"K\", \"density\"}, \"damping\": {\"alpha\"},\n"
      "   \"partition\": {\"kind\": uniform|layers|linear_fraction|tags|sphere|strain, ...},\n"
      "   \"boundary\": {\"fixed\", \"prescribed\", \"forces\", \"gravity\", \"probe\"},\n"
      "   \"solver\": {\"kind\": explicit|static, \"steps\", \"dt\" | \"safety_factor\", \"force_dt\", \"increments\", ...},\n"
      "   \"output\": {\"vtu\", \"vtu_interval\", \"vtu_format\", \"trajectories\", \"trajectory_interval\", \"velocity\"},\n"
      "   \"cuts\": [{\"time\", \"from\", \"to\", \"mode\": \"remove\"|\"separate\"}],\n"
      "   \"threads\": " + std::to_string(hybrid::DhdConfig{}.threads) + ", \"bench\": {\"steps\", \"threads\", \"linear_fraction\", \"repeats\", \"response_set\"}}\n"
      "  --cut-bench: what the config's first cut costs the explicit engine and a precomputing method\n"
      "  Element kinds (partition \"element\", \"linear_element\", \"nonlinear_element\"; the artifact's element_kind\n"
      "  codes): " +
      fem::kind_legend_text() +
      "\n"
      "  Full reference: cpp/apps/dhd_sim.md";
  return app::run_app(argc, argv, info, [](app::AppContext& ctx) {
    const io::JsonReader& cfg = ctx.config();
    const std::string mesh_path = ctx.input(hybrid::read_mesh_path(cfg));
    const mesh::TetMesh mesh = io::read_mesh_artifact(mesh_path);
    const hybrid::DhdConfig config = hybrid::read_dhd_config(cfg, mesh);
    if (!config.strain_reference.empty()) ctx.input(config.strain_reference);
    for (const auto& tool : config.scene.tools)
      if (tool.surface) ctx.input(tool.surface->source());
    ctx.output(config.output.vtu, "/output/vtu");

    if (ctx.flag("--cut-bench")) {
      ctx.write(hybrid::kCutBenchSchema, hybrid::kCutBenchSchemaVersion,
                hybrid::cut_bench(mesh, config, config.bench.repeats, config.bench.response_nodes));
      return;
    }
    if (ctx.flag("--bench")) {
      const auto runs = hybrid::run_bench(mesh, config);
      print_bench(runs);
      ctx.write(hybrid::kBenchSchema, hybrid::kBenchSchemaVersion, hybrid::bench_payload(mesh, config, runs));
      return;
    }

    // Steps, simulated time and steps/s on a terminal; quiet otherwise.
    app::ProgressLine progress_line("dhd_sim", config.explicit_solver.steps);
    dynamics::ProgressFn progress;
    if (progress_line.enabled() && !config.static_solver)
      progress = [&](int steps_done, double time) { progress_line.update(steps_done, time); };
    const hybrid::DhdRun run = hybrid::run_dhd_writing_vtu(mesh, config, progress);
    ctx.write(hybrid::kResultSchema, hybrid::kResultSchemaVersion, hybrid::result_payload(mesh, config, run));
    if (config.model_defaulted)
      std::cerr << "dhd_sim: note: material.model not given: the paper's neo-Hookean form (\"" << config.model
                << "\"); CalculiX and Miller's TLED use \"neo_hookean_decoupled\"\n";
    if (run.explicit_result) {
      const auto& r = *run.explicit_result;
      std::cerr << "dhd_sim: " << r.steps << " explicit steps of " << run.step.dt << " s (critical " << run.critical.dt
                << " s)";
      if (r.step_history.size() > 1)
        std::cerr << ", re-estimated " << r.step_history.size() - 1 << " times on the deformed mesh down to "
                  << r.step_history.back().dt << " s";
      std::cerr << ", " << r.timing.steps_per_second << " steps/s\n";
    }
    else
      std::cerr << "dhd_sim: static equilibrium in " << config.static_options.increments << " increments\n";
    const hybrid::SmallStrainRecord& ss = run.small_strain;
    if (ss.broken())
      std::cerr << "dhd_sim: warning: small-strain element " << ss.element << " ("
                << fem::kind_name(run.kinds[ss.element]) << ") reached a deformation of " << ss.largest << " at t = "
                << ss.time << " s, beyond the " << hybrid::kSmallStrainLimit
                << " under which 000 §2.2.2 takes such elements as valid (small_strain_check)\n";
  });
}
