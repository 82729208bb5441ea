// libFuzzer target: the bytes as rpim_precompute's config file, through run_app (fuzz_app.hpp):
// every config reader (plate, RPIM settings, penalty, solver, dataset, block study, indentation)
// on the config run_app read, each on its own so that one refusal does not hide the others.
// The plates are not assembled (the readers, not the solves, are what is fuzzed here).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_app.hpp"
#include "softsim/meshless/rpim_config.hpp"

namespace {

void read_rpim_config(softsim::app::AppContext& ctx) {
  using softsim::io::JsonReader;
  namespace ml = softsim::meshless;
  const JsonReader& cfg = ctx.config();
  const auto attempt = [](const auto& read) {
    try {
      read();
    } catch (const softsim::InputError&) {
    }
  };
  attempt([&] {
    const auto scene = ml::read_plate_scene(cfg.optional("plate"));
    const auto settings = ml::read_rpim_settings(cfg.optional("rpim"), cfg.optional("penalty"), cfg.optional("solver"));
    const double h = ml::plate_mean_spacing(scene);
    ml::rpim_settings_json(settings, ml::resolve_rbf(settings, h), ml::resolve_support(settings, h), h);
    ml::plate_scene_json(scene);
  });
  attempt([&] { if (cfg.has("dataset")) ml::read_dataset_spec(cfg.at("dataset")); });
  attempt([&] { ml::read_block_study(cfg.optional("block")); });
  attempt([&] { if (cfg.has("indentation")) ml::read_indentation(cfg.at("indentation")); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::run_tool("rpim_precompute", std::string(reinterpret_cast<const char*>(data), size), read_rpim_config);
  return 0;
}
