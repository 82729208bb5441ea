#pragma once
// Whitespace-separated tokens with line numbers, for the ASCII mesh readers: every complaint
// names the file, the line and what was expected. Files that mix text with binary blocks (Gmsh's
// binary .msh) read those blocks with begin_binary / read_bytes; from the first binary block on,
// complaints name the byte offset instead of the line.
#include <cstdint>
#include <string>

namespace softsim::mesh {

class TextTokens {
 public:
  TextTokens(std::string text, std::string source);
  bool at_end();
  std::string next(const std::string& expected);  // InputError at end of file
  std::string peek();
  double next_double(const std::string& expected);
  std::int64_t next_int(const std::string& expected);  // within the 64-bit range
  int next_int32(const std::string& expected);           // within the 32-bit range (a C int)
  // A count of following items: non-negative and no larger than the bytes left in the text
  // (each item takes at least one byte), so a corrupt count cannot trigger a huge allocation.
  std::int64_t next_count(const std::string& expected);
  void expect(const std::string& token);
  void skip_line();          // skips the rest of the current line
  std::string rest_of_line();
  int line() const { return line_; }
  // Raw bytes follow the current line: skips the rest of it, newline included.
  void begin_binary();
  // The next n raw bytes; InputError when fewer are left.
  void read_bytes(void* out, std::size_t n, const std::string& expected);
  std::size_t bytes_left() const { return text_.size() - pos_; }
  // Whether every byte has been read (unlike at_end, skips nothing: an empty line still counts).
  bool exhausted() const { return pos_ >= text_.size(); }
  [[noreturn]] void fail(const std::string& expected, const std::string& got) const;

 private:
  void skip_space();
  std::string text_;
  std::string source_;
  std::size_t pos_ = 0;
  int line_ = 1;
  bool binary_ = false;
};

}  // namespace softsim::mesh
