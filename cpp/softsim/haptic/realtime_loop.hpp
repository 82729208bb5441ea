#pragma once
// The real-time mode: the interface a haptic-device bridge drives. The bridge sends the tool
// tip once per frame, "t x y z" (s, m), and gets back "t fx fy fz" (N, the force on the tool)
// for the same t, as soon as the frame is computed. Two transports:
//   - lines on an input descriptor, answers on an output descriptor (stdin / stdout),
//   - UDP datagrams on loopback, each answered to the session's peer; "end" closes the session.
// The lines' rules (wire_protocol.hpp): every message gets exactly one answer, a frame's force,
// "#" for a comment or "error ..." for anything malformed, and a bad message never ends the
// session. The bridge paces the loop (1 kHz for a device); each frame's wall time from receipt
// to answer is recorded, and a frame longer than the frame period is a deadline miss.
//
// How a session ends, and the exit code haptic_sim gives (cpp/apps/haptic_sim.md):
//   0  "end", the input's end, or max_frames frames;
//   4  the client left: its answers' reader closed (a broken pipe) or, on UDP, it was silent
//      for idle_timeout seconds;
//   5  SIGTERM, SIGINT or SIGHUP.
// In every case the record of what was answered is complete and the artifact is written.
#include <functional>
#include <string>

#include "softsim/haptic/device_safety.hpp"
#include "softsim/haptic/haptic_run.hpp"
#include "softsim/haptic/visual_stream.hpp"

namespace softsim::haptic {

inline constexpr int kExitClientLeft = 4;
inline constexpr int kExitStopped = 5;

struct ServeOptions {
  long max_frames = 0;                  // 0: until the session ends
  double idle_timeout = 5.0;            // udp: s without a datagram from the peer
  ForceLimiter* limiter = nullptr;      // what the device may be sent
  const Workspace* workspace = nullptr; // positions farther are refused (an error answer)
  VisualStream* visual = nullptr;       // the deformed surface after each answer, at its own rate
};

struct ServedSession {
  HapticRecord record;  // record.reports["session"]: how it ended, errors, peers (haptic_sim.md)
  int exit_code = 0;
};

// Serves the lines read from descriptor `in_fd`, answering on `out_fd`.
ServedSession serve_lines(HapticScene& scene, int in_fd, int out_fd, const ServeOptions& options);

// Serves UDP datagrams on 127.0.0.1:`port` (0: a free port). `on_listen` receives the bound
// port before the first datagram is awaited. The first sender is the session's peer; datagrams
// from any other address are ignored and counted.
ServedSession serve_udp(HapticScene& scene, int port, const ServeOptions& options,
                        const std::function<void(int port)>& on_listen);

}  // namespace softsim::haptic
