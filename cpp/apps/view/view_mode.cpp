#include "view_mode.hpp"

#include <filesystem>
#include <iostream>

#include "softsim/io/errors.hpp"
#include "softsim/mesh/tet_mesh.hpp"
#include "view_server.hpp"

#ifndef SOFTSIM_VIEW_WEB_DIR
#define SOFTSIM_VIEW_WEB_DIR ""
#endif

namespace softsim::view {

namespace {

const char* contact_name(haptic::ContactMode m) {
  switch (m) {
    case haptic::ContactMode::grasp: return "grasp";
    case haptic::ContactMode::attach: return "attach";
    case haptic::ContactMode::push: return "push";
    case haptic::ContactMode::tool: return "tool";
  }
  return "grasp";
}

}  // namespace

haptic::HapticRecord run_view(app::AppContext& ctx, const ViewArgs& args, const haptic::HapticConfig& config,
                              haptic::HapticScene& scene, haptic::ForceLimiter& limiter) {
  namespace fs = std::filesystem;
  const std::string web = args.web_root.empty() ? std::string(SOFTSIM_VIEW_WEB_DIR) : args.web_root;
  if (!fs::exists(fs::path(web) / "index.html"))
    throw InputError("view: " + web + ": expected the page (index.html); build the target view_web");
  if (!fs::exists(fs::path(web) / "node_modules/three/build/three.module.js"))
    throw InputError("view: " + web + "/node_modules/three: expected three.js (the target view_web runs npm ci there)");
  if (!args.record.empty()) ctx.output(args.record, "command line: --record");

  // The tip starts at the input's start, where the regions are prepared (as `run` does), so that
  // `run` replays the recorded trajectory from the same state.
  const Eigen::Vector3d start = config.input.at(0);
  scene.prepare(start);
  haptic::ViewLoopOptions loop_options;
  loop_options.latency = args.latency;
  loop_options.max_frames = args.frames;
  loop_options.limiter = &limiter;
  loop_options.state_every = std::max(1, static_cast<int>(std::lround(1.0 / (60 * config.options.frame_step))));
  haptic::ViewLoop loop(scene, start, loop_options);

  const auto box = mesh::bounding_box(scene.model().mesh());
  haptic::ViewHello hello;
  hello.frame_rate = 1.0 / config.options.frame_step;
  hello.contact = contact_name(config.options.contact);
  hello.regions = config.options.use_regions;
  hello.latency = args.latency;
  hello.state_every = loop_options.state_every;
  hello.max_edge = (box.second - box.first).norm();
  hello.probe_stiffness = config.options.probe_stiffness;

  ViewServerOptions server;
  server.host = args.host;
  server.port = args.port;
  server.web_root = web;
  serve_view(loop, hello, server, [&](int port) {
    std::cerr << "haptic_sim: view on http://" << args.host << ":" << port << "/" << std::endl;
  });
  loop.rethrow();
  if (!args.record.empty()) loop.write_trajectory(args.record);
  haptic::HapticRecord record = loop.record();
  record.reports["device_safety"] = limiter.payload();
  return record;
}

}  // namespace softsim::view
