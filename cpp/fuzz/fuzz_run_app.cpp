// libFuzzer target: the bytes as mesher's config file, through run_app (fuzz_app.hpp): read,
// meshed (cuboids of at most 64 cells), checked as the readers check and written at --out.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_app.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::run_tool("mesher", std::string(reinterpret_cast<const char*>(data), size), fuzz::mesher_body);
  return 0;
}
