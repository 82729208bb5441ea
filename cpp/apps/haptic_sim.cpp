// haptic_sim: the 3-D haptic scene (001 §3 on a tetrahedral organ, the model as dhd_sim runs it):
// a tool tip pulls the organ's surface through a spring, once per haptic frame, and the spring's
// force goes back to the device.
//   run:   the configured input (press, slide, growing sine, chirp, recorded) for `frames` frames
//   serve: the real-time loop a device bridge drives, over stdin/stdout or UDP on loopback
//   view:  the live scene with its page in a browser, the pointer as the device (cpp/apps/view/)
// Both write a "haptic_result" artifact: forces, probe positions, contact, frame times, events.
// Config reference: cpp/apps/haptic_sim.md.
#include <unistd.h>

#include <iostream>
#include <memory>

#include "common/app.hpp"
#include "softsim/haptic/haptic_config.hpp"
#include "softsim/haptic/haptic_run.hpp"
#include "softsim/haptic/realtime_loop.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "view/view_args.hpp"
#ifdef SOFTSIM_HAVE_VIEW
#include "view/view_mode.hpp"
#endif

using namespace softsim;

int main(int argc, char** argv) {
  // view's own options (--port, --host, --web, --record, --frames, --latency) leave the arguments first.
  std::vector<std::string> args(argv + 1, argv + argc);
  view::ViewArgs view_args;
  try {
    view_args = view::take_view_args(args);
  } catch (const InputError& e) {
    std::cerr << "haptic_sim: error: " << e.what() << "\n";
    return 2;
  }
  std::vector<char*> rest{argv[0]};
  for (auto& a : args) rest.push_back(a.data());
  app::AppInfo info;
  info.name = "haptic_sim";
  info.summary = "3-D haptic scene at the haptic rate on a dhd_sim model (papers 000, 001): run an input or serve a device";
  info.modes = {"run", "serve", "view"};
  info.needs_out = !view_args.view;  // view: --out optional (the session's artifact when given)
  info.config_help =
      "  {\"model\": {a dhd_sim config with an explicit solver and no probe},\n"
      "   \"frame_rate\": 1000 Hz, \"frames\": 1000 (run),\n"
      "   \"probe\": {\"stiffness\": N/m, \"contact\": \"grasp\"|\"attach\"|\"push\"} | {\"contact\": \"tool\", \"tool_offset\": [x,y,z]},\n"
      "            + \"max_force\": 20 N, \"max_force_step\": 2 N per frame, \"max_distance\": 1 m (what the device may be sent),\n"
      "   \"input\": {\"kind\": \"press\", \"start\": [x,y,z], \"direction\": [x,y,z], \"depth\": m, \"ramp_time\": s}\n"
      "            | {\"kind\": \"slide\", ... as press, \"slide_direction\": [x,y,z], \"speed\": m/s}\n"
      "            | {\"kind\": \"growing_sine\", \"start\", \"direction\", \"amplitude\": m, \"frequency\": Hz, \"growth_time\": s}\n"
      "            | {\"kind\": \"chirp\", \"start\", \"direction\", \"amplitude\": m, \"start_frequency\": Hz, \"end_frequency\": Hz, \"sweep_time\": s}\n"
      "            | {\"kind\": \"recorded\", \"path\": \"file of lines t x y z\"},\n"
      "   \"regions\": {\"radius\": m, \"coupling\": \"condensed\"|\"exchange\", \"secondary_every\": 10, \"interpolate\": true,\n"
      "               \"secondary\": \"static\"|\"implicit\"|\"guyan\", \"modes\": 0 (guyan),\n"
      "               \"precision\": \"double\"|\"single\", \"skip_below\": 0 m,\n"
      "               \"tool_margin\": m (contact tool), \"adaptive\": {\"kind\": \"linear\"|\"threshold\", \"max_radius\": m, ...}}   (001 §5),\n"
      "   \"realtime\": {\"source\": \"stdin\"|\"udp\", \"port\": 0, \"max_frames\": 0, \"idle_timeout\": 5 s, \"announce\": true,\n"
      "                 \"visual\": {\"path\": FILE, \"every\": 33}}}   (serve)\n"
      "  view: haptic_sim view --config FILE [--port 8080] [--host 127.0.0.1] [--record FILE] [--out FILE]\n"
      "        [--frames N] [--latency 0.025] [--web DIR]: the page at http://HOST:PORT/\n"
      "  Full reference: cpp/apps/haptic_sim.md";
  return app::run_app(static_cast<int>(rest.size()), rest.data(), info, [&view_args](app::AppContext& ctx) {
    const io::JsonReader& cfg = ctx.config();
    const std::string mesh_path = ctx.input(haptic::read_haptic_mesh_path(cfg));
    auto mesh = std::make_shared<const mesh::TetMesh>(io::read_mesh_artifact(mesh_path));
    const haptic::HapticConfig config = haptic::read_haptic_config(cfg, *mesh);
    ctx.stream_output(config.realtime.visual.path, "/realtime/visual/path");
    haptic::ForceLimiter limiter(config.safety);
    const haptic::Workspace workspace(*mesh, config.safety.max_distance);
    if (!config.recorded_path.empty()) ctx.input(config.recorded_path);
    for (const auto& tool : config.model.scene.tools)
      if (tool.surface) ctx.input(tool.surface->source());
    haptic::HapticScene scene(mesh, config.model, config.options);
    haptic::HapticRecord record;
    if (ctx.mode == "view") {
#ifdef SOFTSIM_HAVE_VIEW
      record = view::run_view(ctx, view_args, config, scene, limiter);
#else
      throw InputError("view: this haptic_sim was built without the viewer (Boost.Beast was not found at configure time)");
#endif
    } else if (ctx.mode == "serve") {
      const auto& rt = config.realtime;
      // Everything is set up before the device's clock starts: the model above and, with
      // regions, the region at the input's start (its factorisation can take seconds on a fine
      // mesh), so the first answer is a frame like the others. "listening" (udp) or, asked for
      // (realtime.announce), "ready" (stdin) on stderr says so.
      if (config.options.use_regions) scene.prepare(config.input.at(0));
      std::unique_ptr<haptic::VisualStream> visual;
      if (!rt.visual.path.empty()) visual = std::make_unique<haptic::VisualStream>(*mesh, rt.visual);
      const haptic::ServeOptions options{rt.max_frames, rt.idle_timeout, &limiter, &workspace, visual.get()};
      haptic::ServedSession served;
      if (rt.source == haptic::RealtimeConfig::Source::udp) {
        served = haptic::serve_udp(scene, rt.port, options, [](int port) {
          std::cerr << "haptic_sim: listening on udp 127.0.0.1:" << port << std::endl;
        });
      } else {
        if (rt.announce) std::cerr << "haptic_sim: ready" << std::endl;
        served = haptic::serve_lines(scene, STDIN_FILENO, STDOUT_FILENO, options);
      }
      record = std::move(served.record);
      ctx.exit_code = served.exit_code;
    } else {
      record = haptic::run_haptic(scene, config.input, config.frames, &limiter, &workspace);
    }
    if (!ctx.out_path.empty())
      ctx.write(haptic::kHapticSchema, haptic::kHapticSchemaVersion, haptic::haptic_payload(config, scene, record, ctx.mode));
    const auto ft = haptic::summarize_frame_times(record.compute_seconds, config.options.frame_step);
    std::cerr << "haptic_sim: " << record.frames << " frames, " << scene.substeps() << " substeps of " << scene.dt()
              << " s, frame time p50 " << 1e3 * ft.p50 << " ms p99 " << 1e3 * ft.p99 << " ms, " << ft.deadline_misses
              << " deadline misses, " << scene.events().size() << " events\n";
  });
}
