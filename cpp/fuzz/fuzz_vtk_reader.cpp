// libFuzzer target: the legacy VTK reader yields a mesh or an InputError, nothing else.
#include <cstddef>
#include <cstdint>
#include <string>

#include "softsim/io/errors.hpp"
#include "softsim/mesh/vtk_legacy_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    softsim::mesh::read_vtk_legacy(text, "fuzz.vtk");
  } catch (const softsim::InputError&) {
  }
  return 0;
}
