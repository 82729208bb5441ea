// libFuzzer target: the marquardt_fit readers — its config (modes fit and cv), an rpim_dataset
// payload and a fitted model — each tried on the same JSON document. Any input must give a
// value or an InputError: never a crash, undefined behaviour or another exception type.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "softsim/fit/dataset_json.hpp"
#include "softsim/fit/fit_config.hpp"
#include "softsim/fit/model_json.hpp"
#include "softsim/fit/settings_json.hpp"
#include "fuzz_json.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/json_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  nlohmann::json doc;
  if (!parse_fuzz_json(data, size, doc)) return 0;
  using softsim::io::JsonReader;
  namespace fit = softsim::fit;
  try {
    if (doc.is_object())
      for (const bool cv_mode : {false, true})
        fit::fit_settings_to_json(fit::read_fit_config(JsonReader(doc, "fuzz.json"), cv_mode).settings);
  } catch (const softsim::InputError&) {
  }
  try {
    fit::dataset_from_json(JsonReader(doc, "fuzz.json", "/payload"), "fuzz.json");
  } catch (const softsim::InputError&) {
  }
  try {
    fit::model_to_json(fit::model_from_json(JsonReader(doc, "fuzz.json", "/payload/model")));
  } catch (const softsim::InputError&) {
  }
  return 0;
}
