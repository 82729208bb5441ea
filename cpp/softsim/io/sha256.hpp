#pragma once
// SHA-256 of files and strings, for provenance (the hash of every input artifact).
#include <string>

namespace softsim::io {

std::string sha256_hex(const std::string& bytes);
// Throws InputError when the file cannot be read.
std::string sha256_file(const std::string& path);

}  // namespace softsim::io
