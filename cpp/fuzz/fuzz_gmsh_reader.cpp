// libFuzzer target: the Gmsh reader must turn any byte string into either a mesh or an
// InputError — never a crash, a hang, an out-of-range access or another exception type.
#include <cstddef>
#include <cstdint>
#include <string>

#include "softsim/io/errors.hpp"
#include "softsim/mesh/gmsh_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    softsim::mesh::read_gmsh(text, "fuzz.msh");
  } catch (const softsim::InputError&) {
  }
  return 0;
}
