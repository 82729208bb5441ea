#include "softsim/mesh/text_tokens.hpp"

#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "softsim/io/errors.hpp"

namespace softsim::mesh {

TextTokens::TextTokens(std::string text, std::string source)
    : text_(std::move(text)), source_(std::move(source)) {}

void TextTokens::skip_space() {
  while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
    if (text_[pos_] == '\n') ++line_;
    ++pos_;
  }
}

bool TextTokens::at_end() {
  skip_space();
  return pos_ >= text_.size();
}

void TextTokens::fail(const std::string& expected, const std::string& got) const {
  std::string shown = got.size() > 40 ? got.substr(0, 37) + "..." : got;
  const std::string where = binary_ ? "byte " + std::to_string(pos_) : "line " + std::to_string(line_);
  throw InputError(source_ + ": " + where + ": expected " + expected + ", got " +
                   (got.empty() ? "end of file" : "\"" + shown + "\""));
}

std::string TextTokens::next(const std::string& expected) {
  skip_space();
  if (pos_ >= text_.size()) fail(expected, "");
  const std::size_t start = pos_;
  while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  return text_.substr(start, pos_ - start);
}

std::string TextTokens::peek() {
  skip_space();
  const std::size_t save = pos_;
  const int save_line = line_;
  std::string t = pos_ < text_.size() ? next("") : "";
  pos_ = save;
  line_ = save_line;
  return t;
}

double TextTokens::next_double(const std::string& expected) {
  const std::string t = next(expected);
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (end == t.c_str() || *end != '\0' || !std::isfinite(v)) fail(expected, t);
  return v;
}

std::int64_t TextTokens::next_int(const std::string& expected) {
  const std::string t = next(expected);
  char* end = nullptr;
  errno = 0;  // strtoll saturates out of range: ERANGE tells
  const long long v = std::strtoll(t.c_str(), &end, 10);
  if (end == t.c_str() || *end != '\0' || errno == ERANGE) fail(expected + " (a 64-bit integer)", t);
  return v;
}

int TextTokens::next_int32(const std::string& expected) {
  const std::string t = peek();
  const std::int64_t v = next_int(expected);
  if (v < INT_MIN || v > INT_MAX) fail(expected + " (a 32-bit integer)", t);
  return static_cast<int>(v);
}

std::int64_t TextTokens::next_count(const std::string& expected) {
  const std::string t = next(expected);
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(t.c_str(), &end, 10);
  if (end == t.c_str() || *end != '\0' || errno == ERANGE || v < 0 || static_cast<std::size_t>(v) > text_.size() - pos_)
    fail(expected + " (a count no larger than the rest of the file)", t);
  return v;
}

void TextTokens::expect(const std::string& token) {
  const std::string t = next("\"" + token + "\"");
  if (t != token) fail("\"" + token + "\"", t);
}

void TextTokens::skip_line() { rest_of_line(); }

void TextTokens::begin_binary() {
  rest_of_line();
  binary_ = true;
}

void TextTokens::read_bytes(void* out, std::size_t n, const std::string& expected) {
  if (n > bytes_left()) fail(expected, "");
  std::memcpy(out, text_.data() + pos_, n);
  pos_ += n;
}

std::string TextTokens::rest_of_line() {
  const std::size_t start = pos_;
  while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  std::string out = text_.substr(start, pos_ - start);
  if (pos_ < text_.size()) {
    ++pos_;
    ++line_;
  }
  return out;
}

}  // namespace softsim::mesh
