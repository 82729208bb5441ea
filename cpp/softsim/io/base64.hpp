#pragma once
// Base64 (RFC 4648, standard alphabet, '=' padding), for the inline binary arrays of VTK XML
// files (vtu_writer.hpp, mesh/vtu_reader.hpp).
#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>

namespace softsim::io {

// Encodes a byte stream piece by piece: bytes put in several calls are encoded as one stream
// (VTK's uncompressed inline arrays encode the byte-count header and the data together).
class Base64Writer {
 public:
  explicit Base64Writer(std::ostream& out) : out_(out) {}
  void put(const void* data, std::size_t bytes);
  void finish();  // writes the last partial group with padding

 private:
  std::ostream& out_;
  unsigned char pending_[3] = {0, 0, 0};
  int held_ = 0;
};

std::string base64_encode(std::string_view bytes);

// Decodes, skipping whitespace. Padding may close a group in the middle of the text as well as
// at its end: some writers (VTK among them) encode an array's header and its data as two
// separately padded streams placed one after the other. nullopt on any other character, or on
// a group cut short.
std::optional<std::string> base64_decode(std::string_view text);

}  // namespace softsim::io
