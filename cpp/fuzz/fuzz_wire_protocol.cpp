// libFuzzer target: the bytes as one message of the device protocol (haptic_sim serve's lines and
// datagrams, wire_protocol.hpp): every message is classified, an error quotes a short excerpt
// whatever the message's length, and a frame's answer fits its buffer with t echoed unchanged.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "softsim/haptic/wire_protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace softsim::haptic;
  const std::string_view line(reinterpret_cast<const char*>(data), size);
  WireLine w;
  parse_wire_line(line, w);
  if (w.kind == WireLine::Kind::error && w.error.size() > 120 + 4 * kExcerptBytes) std::abort();
  if (w.kind == WireLine::Kind::frame) {
    if (!w.position.allFinite() || w.t_text.empty() || w.t_text.size() > kMaxLineBytes) std::abort();
    char answer[kMaxLineBytes + 256];
    const std::size_t n = format_force_answer(answer, sizeof answer, w.t_text, w.position);
    if (n >= sizeof answer || std::string_view(answer, w.t_text.size()) != w.t_text) std::abort();
  }
  return 0;
}
