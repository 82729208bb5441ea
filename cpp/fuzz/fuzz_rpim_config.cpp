// libFuzzer target: every rpim_precompute config reader (plate, RPIM settings, penalty, solver,
// dataset, block study, indentation) on one JSON document. Any input must give settings or an
// InputError: never a crash, undefined behaviour or another exception type.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzz_json.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/meshless/rpim_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  nlohmann::json doc;
  if (!parse_fuzz_json(data, size, doc)) return 0;
  using softsim::io::JsonReader;
  namespace ml = softsim::meshless;
  const JsonReader cfg(doc, "fuzz.json");
  // Each reader on its own, so that one refusal does not hide the others.
  try {
    if (!doc.is_object()) cfg.fail("a JSON object");
    const auto scene = ml::read_plate_scene(cfg.optional("plate"));
    const auto settings = ml::read_rpim_settings(cfg.optional("rpim"), cfg.optional("penalty"), cfg.optional("solver"));
    const double h = ml::plate_mean_spacing(scene);
    ml::rpim_settings_json(settings, ml::resolve_rbf(settings, h), ml::resolve_support(settings, h), h);
    ml::plate_scene_json(scene);
  } catch (const softsim::InputError&) {
  }
  try {
    if (doc.is_object() && doc.contains("dataset")) ml::read_dataset_spec(cfg.at("dataset"));
  } catch (const softsim::InputError&) {
  }
  try {
    if (doc.is_object()) ml::read_block_study(cfg.optional("block"));
  } catch (const softsim::InputError&) {
  }
  try {
    if (doc.is_object() && doc.contains("indentation")) ml::read_indentation(cfg.at("indentation"));
  } catch (const softsim::InputError&) {
  }
  return 0;
}
