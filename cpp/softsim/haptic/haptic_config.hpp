#pragma once
// The haptic_sim configuration (cpp/apps/haptic_sim.md): the organ model exactly as dhd_sim
// reads it ("model"), the frame rate, the probe, the generated or recorded input, and the
// real-time loop's source. Read strictly: unknown keys and bad values are InputErrors naming
// the file and JSON pointer.
#include <string>

#include "softsim/haptic/device_safety.hpp"
#include "softsim/haptic/haptic_scene.hpp"
#include "softsim/haptic/probe_path.hpp"
#include "softsim/haptic/visual_stream.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/io/json_reader.hpp"

namespace softsim::haptic {

struct RealtimeConfig {
  enum class Source { stdin_lines, udp };
  Source source = Source::stdin_lines;
  int port = 0;          // udp: the loopback port to listen on (0: any free port, printed)
  long max_frames = 0;   // 0: until the input ends
  double idle_timeout = 5.0;  // udp: s without a datagram before the client counts as gone, [1e-3, 86400]
  bool announce = true;       // stdin: "haptic_sim: ready" on stderr once set up (udp announces its port)
  VisualConfig visual;        // the deformed surface at a lower rate (visual_stream.hpp)
};

struct HapticConfig {
  hybrid::DhdConfig model;
  HapticOptions options;
  ProbePath input;
  std::string recorded_path;  // input.kind "recorded": the file read
  long frames = 1000;         // run mode
  RealtimeConfig realtime;
  DeviceSafetyConfig safety;  // probe.max_force, max_force_step, max_distance
};

// The model's mesh path (the mesh must be loaded before the rest can be read).
std::string read_haptic_mesh_path(const io::JsonReader& config);

// The whole config against the loaded mesh; reads a recorded trajectory file.
HapticConfig read_haptic_config(const io::JsonReader& config, const mesh::TetMesh& mesh);

}  // namespace softsim::haptic
