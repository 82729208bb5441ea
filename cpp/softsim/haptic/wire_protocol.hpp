#pragma once
// The device protocol's lines (cpp/apps/haptic_sim.md, "The protocol"), one rule for stdin and
// UDP alike:
//   - a message is one line of at most kMaxLineBytes bytes (the newline not counted);
//   - "t x y z": four finite numbers (s, m) is a frame; its answer is "t fx fy fz", with t
//     echoed byte for byte as it was received (an epoch-seconds clock comes back unchanged);
//   - a blank line, or one whose first non-blank character is '#', is no frame: answered "#";
//   - "end" closes the session;
//   - anything else is answered "error <where>: <what>", quoting at most kExcerptBytes bytes of
//     the message (non-printable bytes escaped), and the session goes on.
#include <cstddef>
#include <string>
#include <string_view>

#include <Eigen/Core>

namespace softsim::haptic {

inline constexpr std::size_t kMaxLineBytes = 512;
inline constexpr std::size_t kExcerptBytes = 40;

// At most kExcerptBytes of `text`, quoted; control and non-ASCII bytes as \xNN; "..." when cut.
std::string excerpt(std::string_view text);

struct WireLine {
  enum class Kind { frame, comment, end, error };
  Kind kind = Kind::error;
  std::string_view t_text;  // frame: the time token as received
  double t = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::string error;  // error: what was expected and what came (no location)
};

// Classifies one message (without its newline; it may hold any byte, NUL included).
void parse_wire_line(std::string_view line, WireLine& out);

// "t fx fy fz\n" into `buffer`; the force at round-trip precision (%.17g). The length written.
std::size_t format_force_answer(char* buffer, std::size_t size, std::string_view t_text, const Eigen::Vector3d& f);

}  // namespace softsim::haptic
