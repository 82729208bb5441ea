#include "softsim/io/base64.hpp"

#include <cctype>
#include <sstream>

namespace softsim::io {

namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int value_of(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

void encode_group(const unsigned char* in, int n, char out[4]) {
  const unsigned v = (unsigned(in[0]) << 16) | (n > 1 ? unsigned(in[1]) << 8 : 0u) | (n > 2 ? unsigned(in[2]) : 0u);
  out[0] = kAlphabet[(v >> 18) & 63];
  out[1] = kAlphabet[(v >> 12) & 63];
  out[2] = n > 1 ? kAlphabet[(v >> 6) & 63] : '=';
  out[3] = n > 2 ? kAlphabet[v & 63] : '=';
}

}  // namespace

void Base64Writer::put(const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  char group[4];
  while (bytes > 0) {
    pending_[held_++] = *p++;
    --bytes;
    if (held_ == 3) {
      encode_group(pending_, 3, group);
      out_.write(group, 4);
      held_ = 0;
    }
  }
}

void Base64Writer::finish() {
  if (held_ == 0) return;
  char group[4];
  encode_group(pending_, held_, group);
  out_.write(group, 4);
  held_ = 0;
}

std::string base64_encode(std::string_view bytes) {
  std::ostringstream out;
  Base64Writer w(out);
  w.put(bytes.data(), bytes.size());
  w.finish();
  return out.str();
}

std::optional<std::string> base64_decode(std::string_view text) {
  std::string out;
  out.reserve(text.size() / 4 * 3);
  int group[4];
  int n = 0, pad = 0;
  for (char c : text) {
    if (std::isspace(static_cast<unsigned char>(c))) continue;
    if (c == '=') {
      if (n < 2) return std::nullopt;  // "x===" or "====" cannot close a group
      ++pad;
      group[n++] = 0;
    } else {
      const int v = value_of(c);
      if (v < 0 || pad > 0) return std::nullopt;  // data after padding within one group
      group[n++] = v;
    }
    if (n == 4) {
      const unsigned v = (unsigned(group[0]) << 18) | (unsigned(group[1]) << 12) | (unsigned(group[2]) << 6) |
                         unsigned(group[3]);
      out.push_back(static_cast<char>((v >> 16) & 255));
      if (pad < 2) out.push_back(static_cast<char>((v >> 8) & 255));
      if (pad < 1) out.push_back(static_cast<char>(v & 255));
      n = 0;
      pad = 0;
    }
  }
  if (n != 0) return std::nullopt;
  return out;
}

}  // namespace softsim::io
