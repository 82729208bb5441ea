#pragma once
// The viewer's wire protocol, "softsim-view" version 1 (cpp/apps/haptic_sim.md, "The live scene
// in a browser"): JSON text messages over a WebSocket, plus one binary message of positions after
// each state. Client to server:
//   {"type": "hello", "protocol": 1, "states": "push"}     optional; a different version is refused;
//                                                          "pull": a state only after each "next"
//   {"type": "next"}                                       pull: send the newest state once
//   {"type": "sample", "t": s, "p": [x, y, z], "blade": false, "edge": [ex, ey, ez]}
//                                                          the tool tip on the sender's clock
//   {"type": "stop"}                                       ends the session (artifact, trajectory)
// Server to client: "hello" (protocol, frame rate, set-up), "mesh" (reference positions and live
// surface triangles; again after each cut), "state" (then the binary positions), "error".
// Parsing never throws: a bad message is an error string for that connection only.
#include <cstdint>
#include <string>

#include "softsim/haptic/view_pointer.hpp"
#include "softsim/haptic/view_state.hpp"

namespace softsim::haptic {

inline constexpr int kViewProtocol = 1;
inline constexpr const char* kViewProtocolName = "softsim-view";
inline constexpr std::size_t kViewMaxMessage = 4096;  // bytes: a sample is well under 300

struct ClientMessage {
  enum class Kind { hello, sample, next, stop, invalid };
  Kind kind = Kind::invalid;
  bool pull = false;  // hello: states on request ("next") instead of at the server's rate
  PointerSample sample;
  std::string error;  // kind invalid: what was expected
};

// `last_t`: the previous sample's time on this connection (samples must increase); `max_edge`:
// the longest blade edge accepted (m).
ClientMessage parse_client_message(const std::string& text, double last_t, bool has_last, double max_edge);

struct ViewHello {
  double frame_rate = 1000;
  std::string contact;  // grasp, attach, push, tool
  bool regions = false;
  double latency = 0;   // s, the pointer's play-out delay
  int state_every = 16;
  double max_edge = 0;  // m
  double probe_stiffness = 0;
};
std::string format_hello(const ViewHello& h);
std::string format_mesh(const ViewTopology& t);
std::string format_state(const ViewState& s);
std::string format_error(const std::string& message);
// The binary message after a state: 3 float32 per node (x = X + u), then, with regions, one
// byte per node (0 far field, 1 primary interior, 2 interface); little-endian.
void format_positions(const ViewState& s, std::string& out);

}  // namespace softsim::haptic
