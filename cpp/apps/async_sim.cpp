// async_sim: the haptic loop of 001 §3 on the 1-D model of 001 §6, solved as a whole at the
// haptic rate, as linked asynchronous regions (001 §5) and exactly (matrix exponential);
// writes forces, force errors, peak forces and the speed gain as an "async_run" artifact.
#include <iostream>
#include <string>

#include "common/app.hpp"
#include "common/progress_line.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/multirate/run_config.hpp"

using namespace softsim;

int main(int argc, char** argv) {
  app::AppInfo info;
  info.name = "async_sim";
  info.summary = "linked asynchronous FEM regions for haptics (001): whole model vs regions vs exact";
  info.config_help =
      "  {\"model\": {\"kind\": \"bar\", \"nodes\": 40, \"length\": m, \"area\": m^2, \"youngs_modulus\": Pa,\n"
      "             \"density\": kg/m^3, \"damping\": {\"ratio\": r} | {\"alpha\": 1/s}},\n"
      "   \"haptics\": {\"rate\": 1000 Hz, \"duration\": s, \"probe_stiffness\": N/m},\n"
      "   \"input\": {\"kind\": \"chirp\"|\"step\"|\"ramp_hold\"|\"growing_sine\", \"amplitude\": m, ...},\n"
      "   \"solver\": {\"kind\": \"static\"|\"implicit\"|\"explicit\", \"implicit_scheme\": \"newmark\"|\"backward_euler\",\n"
      "              \"explicit_variant\": \"central\"|\"backward_damping\"},\n"
      "   \"linear_solver\": \"sparse\"|\"dense\", \"check_stability\": true,\n"
      "   \"async\": {\"primary\": {\"nodes\": n} | {\"policy\": \"linear\"|\"threshold\", ...},\n"
      "             \"primary_solver\": {...}, \"secondary\": [{\"every\": 20, \"nodes\": 0, \"solver\": {...}}],\n"
      "             \"interpolate\": true, \"merge_full_rate\": true},\n"
      "   \"reference\": true, \"timing_repeats\": 3, \"series_every\": 0, \"frequency_bin\": 0.5 Hz}\n"
      "  Full reference: cpp/apps/async_sim.md";
  return app::run_app(argc, argv, info, [](app::AppContext& ctx) {
    const io::JsonReader& cfg = ctx.config();
    // read_run_config refuses a run over the memory or work limit (multirate/run_memory.hpp).
    multirate::RunConfig config = multirate::read_run_config(cfg);
    multirate::ModelSummary model;
    const multirate::ReducedSystem system = multirate::build_system(config, model);
    // Frames over every loop and the simulated time on a terminal; quiet otherwise.
    app::ProgressLine progress_line("async_sim", multirate::total_loop_frames(config.comparison), "frame");
    if (progress_line.enabled())
      config.comparison.progress = [&](long long done, double time) { progress_line.update(done, time); };
    const multirate::ComparisonResult result = multirate::run_configured_comparison(system, config);
    ctx.write(multirate::kAsyncRunSchema, multirate::kAsyncRunSchemaVersion,
              multirate::make_payload(config, model, result));
    std::cerr << "async_sim: " << model.free_nodes << " free nodes, whole peak force "
              << result.whole_summary.peak_force << " N";
    if (config.comparison.async)
      std::cerr << ", async error vs whole " << 100.0 * result.async_vs_whole.rms_relative << " % (rms), speed gain "
                << result.whole_summary.seconds_per_frame / result.async_summary.seconds_per_frame;
    std::cerr << "\n";
  });
}
