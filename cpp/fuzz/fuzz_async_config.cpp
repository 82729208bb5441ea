// libFuzzer target: the bytes as async_sim's config file, through run_app (fuzz_app.hpp) with
// async_sim's body: the config reader with its memory and work estimates, the model it builds,
// and for small runs (at most 50 nodes and 200 frames) the comparison and the artifact.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_app.hpp"
#include "softsim/multirate/run_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::run_tool("async_sim", std::string(reinterpret_cast<const char*>(data), size), [](softsim::app::AppContext& ctx) {
    namespace mr = softsim::multirate;
    const mr::RunConfig config = mr::read_run_config(ctx.config());
    if (config.bar.nodes > 200) return;  // the build, not the reader, would dominate the time
    mr::ModelSummary model;
    const mr::ReducedSystem system = mr::build_system(config, model);
    if (config.bar.nodes > 50 || config.comparison.loop.frames > 200) return;
    const mr::ComparisonResult result = mr::run_configured_comparison(system, config);
    ctx.write(mr::kAsyncRunSchema, mr::kAsyncRunSchemaVersion, mr::make_payload(config, model, result));
  });
  return 0;
}
