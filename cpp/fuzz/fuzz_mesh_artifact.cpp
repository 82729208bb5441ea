// libFuzzer target: JSON parsing plus the strict mesh-artifact reader (indices, orientation,
// tag sizes). Any input must give a mesh or an InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzz_json.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/mesh/surface.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  nlohmann::json doc;
  if (!parse_fuzz_json(data, size, doc)) return 0;
  try {
    const softsim::io::JsonReader payload(doc, "fuzz.json");
    const auto mesh = softsim::io::mesh_from_json(payload);
    softsim::mesh::extract_boundary(mesh, "fuzz.json");
  } catch (const softsim::InputError&) {
  }
  return 0;
}
