#pragma once
// The real-time mode: the interface a haptic-device bridge drives. The bridge sends the tool
// tip once per frame, "t x y z" (s, m), and gets back "t fx fy fz" (N, the force on the tool)
// for the same t, as soon as the frame is computed. Two transports:
//   - lines on an input stream, answers on an output stream (stdin / stdout),
//   - UDP datagrams on loopback, each answered to its sender; "end" closes the session.
// The bridge paces the loop (1 kHz for a device); each frame's wall time from receipt to answer
// is recorded, and a frame longer than the frame period is a deadline miss.
#include <functional>
#include <iosfwd>

#include "softsim/haptic/haptic_run.hpp"
#include "softsim/haptic/visual_stream.hpp"

namespace softsim::haptic {

// Serves lines from `in` until it ends (or `max_frames` > 0 frames). InputError, naming the
// line, for a malformed line, a time that does not increase or a position that is not finite.
// With `visual`, the deformed surface goes to it after each answer (at its own rate).
HapticRecord serve_lines(HapticScene& scene, std::istream& in, std::ostream& out, long max_frames,
                         VisualStream* visual = nullptr);

// Serves UDP datagrams on 127.0.0.1:`port` (0: a free port) until "end" (or `max_frames`).
// `on_listen` receives the bound port before the first datagram is awaited. A client silent for
// `idle_timeout` seconds is an InputError (the bridge went away without "end").
HapticRecord serve_udp(HapticScene& scene, int port, long max_frames, double idle_timeout,
                       const std::function<void(int port)>& on_listen, VisualStream* visual = nullptr);

}  // namespace softsim::haptic
