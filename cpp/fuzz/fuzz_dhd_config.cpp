// libFuzzer target: the bytes as dhd_sim's config file, through run_app (fuzz_app.hpp) with
// dhd_sim's body (fuzz_dhd.hpp) on a fixed 27-node cuboid artifact: the config reader, the
// partition, the step choice, a few steps of the configured solver and the result artifact.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_dhd.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& mesh = fuzz::cuboid_artifact();
  fuzz::run_tool("dhd_sim", std::string(reinterpret_cast<const char*>(data), size),
                 [&](softsim::app::AppContext& ctx) { fuzz::dhd_body(ctx, mesh); });
  return 0;
}
