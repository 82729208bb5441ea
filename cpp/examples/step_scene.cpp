// A complete program that steps a scene the way a haptic simulator does: once per 1 ms frame,
// move the tool tip, advance the explicit engine to the frame's end, read the force the device
// renders. The scene is dhd_sim's (hybrid::DhdScene, the same config and engine), here the
// paper's 5-tetrahedron cuboid (000 §2.2.1) held at the bottom with a probe spring on its top.
//
//   step_scene [out.csv]     writes time, tip depth and force on the tool, one line per frame
//
// The frame clock: the explicit step dt comes from the mesh (000 eq. 34) and need not divide
// 1 ms, so each frame takes the whole steps that bring the simulated time to the frame's end
// (none when dt is longer than a frame); simulated time then follows the frames.
//
// Exit status 0 when the run shows what a press must (the force on the tool points up and grows
// with the depth, the simulated time ends within one step of the frames' time), 1 otherwise.
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/hybrid/dhd_scene.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/mesh/cuboid.hpp"

using namespace softsim;

namespace {

constexpr double kFrame = 1e-3;      // haptic frame (s): 1 kHz
constexpr int kPressFrames = 500;    // tip pushed 2 mm down over 0.5 s ...
constexpr int kFrames = 700;         // ... then held for 0.2 s
constexpr double kDepth = 2e-3;      // m

// dhd_sim's config (cpp/apps/dhd_sim.md): 000 §3.1's tissue, decoupled neo-Hookean elements
// everywhere, the bottom held, a 200 N/m spring from the tool tip to the top node nearest the
// middle. "mesh" names the mesh a caller loads (dhd_sim: a mesher artifact); here it is only a
// label, the mesh is built in memory.
nlohmann::json scene_config() {
  return nlohmann::json::parse(R"json({
    "mesh": "cuboid built in memory (mesh::make_cuboid)",
    "material": {"model": "neo_hookean_decoupled", "E": 5000, "nu": 0.35, "density": 1000},
    "damping": {"alpha": 30},
    "boundary": {"fixed": ["bottom"],
                 "probe": {"nearest": [0.05, 0.05, 0.04], "stiffness": 200, "displacement": [0, 0, 0]}},
    "solver": {"kind": "explicit"}
  })json");
}

}  // namespace

int main(int argc, char** argv) {
  try {
    mesh::CuboidSpec spec;
    spec.cells = {10, 10, 4};
    spec.size = Eigen::Vector3d(0.1, 0.1, 0.04);
    auto mesh = std::make_shared<const mesh::TetMesh>(mesh::make_cuboid(spec));
    const nlohmann::json config = scene_config();
    hybrid::DhdScene scene(mesh, hybrid::read_dhd_config(io::JsonReader(config, "step_scene"), *mesh));

    const Eigen::Vector3d start = scene.probe_position();
    std::vector<double> depth(kFrames), force(kFrames);
    for (int frame = 0; frame < kFrames; ++frame) {
      depth[frame] = kDepth * std::min(1.0, (frame + 1.0) / kPressFrames);
      scene.set_probe_position(start - Eigen::Vector3d(0, 0, depth[frame]));
      const double frame_end = (frame + 1) * kFrame;
      const int steps = static_cast<int>(std::ceil((frame_end - scene.time()) / scene.dt() - 1e-9));
      if (steps > 0) scene.step(steps);
      // The spring pulls its node towards the tip (down); the tool feels the opposite.
      force[frame] = -scene.probe_force().z();
    }

    std::FILE* out = argc > 1 ? std::fopen(argv[1], "w") : stdout;
    if (!out) {
      std::fprintf(stderr, "step_scene: error: cannot write %s\n", argv[1]);
      return 2;
    }
    std::fprintf(out, "time (s),tip depth (mm),force on the tool (N)\n");
    for (int frame = 0; frame < kFrames; ++frame)
      std::fprintf(out, "%.3f,%.4f,%.6g\n", (frame + 1) * kFrame, 1e3 * depth[frame], force[frame]);
    if (out != stdout) std::fclose(out);

    // What the run must show.
    int failures = 0;
    auto check = [&](bool ok, const char* what) {
      std::fprintf(stderr, "%s %s\n", ok ? "ok  " : "FAIL", what);
      if (!ok) ++failures;
    };
    const double end = kFrames * kFrame;
    std::fprintf(stderr, "dt = %.4g ms, %d steps for %d frames of 1 ms, t = %.4f s; force at %.1f mm: %.4g N\n",
                 1e3 * scene.dt(), scene.steps_done(), kFrames, scene.time(), 1e3 * kDepth, force.back());
    check(scene.time() >= end - 1e-12 && scene.time() < end + scene.dt(), "simulated time follows the 1 ms frames");
    check(force.back() > 0, "the tissue pushes the tool back up");
    check(force[kPressFrames - 1] > 2 * force[kPressFrames / 4 - 1], "the force grows with the depth");
    return failures ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "step_scene: error: %s\n", e.what());
    return 1;
  }
}
