// libFuzzer target: the bytes as the tet_mesh artifact a fixed dhd_sim config names, through
// run_app (fuzz_app.hpp) with dhd_sim's body (fuzz_dhd.hpp): the artifact envelope, the strict
// mesh reader (indices, orientation, tag sizes), the boundary and node sets a run uses.
#include <cstddef>
#include <cstdint>

#include "fuzz_dhd.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string mesh = fuzz::write_scratch("mesh.json", data, size);
  const nlohmann::json config = {
      {"mesh", mesh},
      {"material", {{"model", "neo_hookean_paper"}, {"E", 5000}, {"nu", 0.35}, {"density", 1000}}},
      {"boundary", {{"fixed", {"bottom"}}, {"prescribed", {{{"set", "top"}, {"displacement", {0, 0, -0.001}}}}}}},
      {"solver", {{"kind", "explicit"}, {"steps", 2}}}};
  fuzz::run_tool("dhd_sim", config.dump(), [](softsim::app::AppContext& ctx) { fuzz::dhd_body(ctx, ""); });
  return 0;
}
