#include "softsim/haptic/wire_protocol.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace softsim::haptic {

std::string excerpt(std::string_view text) {
  std::string q = "\"";
  const std::size_t n = std::min(text.size(), kExcerptBytes);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\') {
      q += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      q += hex;
    }
  }
  q += text.size() > n ? "\"..." : "\"";
  return q;
}

namespace {

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

}  // namespace

void parse_wire_line(std::string_view line, WireLine& out) {
  out.error.clear();
  if (line.size() > kMaxLineBytes) {
    out.kind = WireLine::Kind::error;
    out.error = "expected a line of at most " + std::to_string(kMaxLineBytes) + " bytes, got " +
                std::to_string(line.size()) + " bytes starting " + excerpt(line);
    return;
  }
  if (line.find('\0') != std::string_view::npos) {
    out.kind = WireLine::Kind::error;
    out.error = "expected text \"t x y z\", got a NUL byte in " + excerpt(line);
    return;
  }
  std::size_t i = 0;
  while (i < line.size() && blank(line[i])) ++i;
  if (i == line.size() || line[i] == '#') {
    out.kind = WireLine::Kind::comment;
    return;
  }
  std::size_t e = line.size();
  while (e > i && blank(line[e - 1])) --e;
  if (line.substr(i, e - i) == "end") {
    out.kind = WireLine::Kind::end;
    return;
  }
  // Four tokens, each a whole finite number. The message is copied so that strtod stops at its
  // end (it is at most kMaxLineBytes).
  char text[kMaxLineBytes + 1];
  std::memcpy(text, line.data(), line.size());
  text[line.size()] = '\0';
  double v[4];
  int n = 0;
  std::size_t p = i;
  while (p < e) {
    if (n == 4) {
      out.kind = WireLine::Kind::error;
      out.error = "expected 4 numbers \"t x y z\", got more in " + excerpt(line);
      return;
    }
    std::size_t q = p;
    while (q < e && !blank(line[q])) ++q;
    char* end = nullptr;
    v[n] = std::strtod(text + p, &end);
    if (end != text + q) {
      out.kind = WireLine::Kind::error;
      out.error = "expected a number, got " + excerpt(line.substr(p, q - p));
      return;
    }
    if (!std::isfinite(v[n])) {
      out.kind = WireLine::Kind::error;
      out.error = "expected a finite number, got " + excerpt(line.substr(p, q - p));
      return;
    }
    if (n == 0) out.t_text = line.substr(p, q - p);
    ++n;
    p = q;
    while (p < e && blank(line[p])) ++p;
  }
  if (n != 4) {
    out.kind = WireLine::Kind::error;
    out.error = "expected 4 numbers \"t x y z\", got " + std::to_string(n);
    return;
  }
  out.kind = WireLine::Kind::frame;
  out.t = v[0];
  out.position = Eigen::Vector3d(v[1], v[2], v[3]);
}

std::size_t format_force_answer(char* buffer, std::size_t size, std::string_view t_text, const Eigen::Vector3d& f) {
  const int n = std::snprintf(buffer, size, "%.*s %.17g %.17g %.17g\n", static_cast<int>(t_text.size()), t_text.data(),
                              f.x(), f.y(), f.z());
  return n < 0 ? 0 : std::min(static_cast<std::size_t>(n), size - 1);
}

}  // namespace softsim::haptic
