#pragma once
// Files are written to a temporary sibling and renamed into place, so a reader never sees a
// half-written artifact and a failed run leaves nothing behind. The path is checked first and
// recorded once in place (io/output_guard.hpp).
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>

namespace softsim::io {

void write_file_atomic(const std::string& path, const std::string& content);
// Streams through a writer callback (for large files such as VTU) with the same guarantee.
void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& writer);

// Reads a whole input file; InputError when it cannot be opened, is not a regular file (a
// device such as /dev/zero never ends) or is larger than max_input_bytes() (io/limits.hpp).
std::string read_text_file(const std::string& path);
// The checks of read_text_file without the reading (a file hashed or handed to another library):
// the file's size in bytes.
std::uint64_t require_input_file(const std::string& path);

}  // namespace softsim::io
