// libFuzzer target: the bytes as marquardt_fit's config file, through run_app (fuzz_app.hpp):
// the fit config reader (modes fit and cv) on the config run_app read, and the rpim_dataset payload and fitted
// model readers on the same document (what an input artifact holds), each on its own.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_app.hpp"
#include "softsim/fit/dataset_json.hpp"
#include "softsim/fit/fit_config.hpp"
#include "softsim/fit/model_json.hpp"
#include "softsim/fit/settings_json.hpp"

namespace {

void read_fit_inputs(softsim::app::AppContext& ctx) {
  using softsim::io::JsonReader;
  namespace fit = softsim::fit;
  const auto attempt = [](const auto& read) {
    try {
      read();
    } catch (const softsim::InputError&) {
    }
  };
  for (const bool cv_mode : {false, true})
    attempt([&] { fit::fit_settings_to_json(fit::read_fit_config(ctx.config(), cv_mode).settings); });
  attempt([&] { fit::dataset_from_json(JsonReader(ctx.config_json, ctx.config_path, "/payload"), ctx.config_path); });
  attempt([&] { fit::model_to_json(fit::model_from_json(JsonReader(ctx.config_json, ctx.config_path, "/payload/model"))); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::run_tool("marquardt_fit", std::string(reinterpret_cast<const char*>(data), size), read_fit_inputs);
  return 0;
}
