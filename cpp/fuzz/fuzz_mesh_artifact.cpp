// libFuzzer target: JSON parsing plus the strict mesh-artifact reader (indices, orientation,
// tag sizes). Any input must give a mesh or an InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "softsim/io/errors.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/mesh/surface.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    return 0;
  }
  try {
    const softsim::io::JsonReader payload(doc, "fuzz.json");
    const auto mesh = softsim::io::mesh_from_json(payload);
    softsim::mesh::extract_boundary(mesh, "fuzz.json");
  } catch (const softsim::InputError&) {
  }
  return 0;
}
