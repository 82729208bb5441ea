// libFuzzer target: the async_sim config reader (multirate::read_run_config) and the model it
// builds. Any input must give a model or an InputError: never a crash, undefined behaviour or
// another exception type. Large models are skipped after reading (the build, not the reader,
// would dominate the time).
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzz_json.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/multirate/run_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  nlohmann::json doc;
  if (!parse_fuzz_json(data, size, doc)) return 0;
  if (!doc.is_object()) return 0;
  try {
    const softsim::io::JsonReader cfg(doc, "fuzz.json");
    const softsim::multirate::RunConfig config = softsim::multirate::read_run_config(cfg);
    if (config.bar.nodes > 200) return 0;
    softsim::multirate::ModelSummary summary;
    softsim::multirate::build_system(config, summary);
  } catch (const softsim::InputError&) {
  } catch (const softsim::NumericalError&) {
  }
  return 0;
}
