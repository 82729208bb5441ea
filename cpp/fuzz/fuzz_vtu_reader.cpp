// libFuzzer target: the VTU reader yields a mesh or an InputError, nothing else.
#include <cstddef>
#include <cstdint>
#include <string>

#include "softsim/io/errors.hpp"
#include "softsim/mesh/vtu_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    softsim::mesh::read_vtu(bytes, "fuzz.vtu");
  } catch (const softsim::InputError&) {
  }
  return 0;
}
