// libFuzzer target: the bytes as a config file given to run_app, the entry point of every
// executable, with mesher's body (a cuboid of at most 64 cells, so each input stays quick). This
// is the path of a real run: the config is read from a file (regular-file and size checks, the
// nesting bound, duplicate keys), copied into the provenance, scanned for output conflicts, read
// strictly, meshed, checked as the readers check and written atomically at --out. Any input must
// end in exit 0, 2 or 3 - never a crash, a hang, undefined behaviour or exit 1.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

#include "common/app.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/io/mesher_config.hpp"
#include "softsim/mesh/quality.hpp"

namespace {

std::string scratch(const char* what) {
  return std::string("/tmp/softsim-fuzz-") + std::to_string(::getpid()) + "-" + what;
}

void mesher_body(softsim::app::AppContext& ctx) {
  using namespace softsim;
  io::MesherConfig config = io::read_mesher_config(ctx.config());
  ctx.output(config.vtu, "/vtu");
  if (config.from_file) return;  // a path of the fuzzer's choosing is not read
  const auto& cells = config.cuboid.cells;
  if (static_cast<long long>(cells[0]) * cells[1] * cells[2] > 64) return;
  const mesh::TetMesh m = io::build_mesh(config);
  nlohmann::json payload = io::mesher_payload(m, mesh::quality_report(m, config.sliver_threshold_deg), config.source);
  io::check_built_mesh(payload, ctx.config_path);
  ctx.write(io::kMeshSchema, io::kMeshSchemaVersion, std::move(payload));  // never the config's vtu
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string config = scratch("config.json");
  static const std::string out = scratch("out.json");
  {
    std::ofstream f(config, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  std::string a0 = "mesher", a1 = "--config", a3 = "--out";
  std::string a2 = config, a4 = out;
  char* argv[] = {a0.data(), a1.data(), a2.data(), a3.data(), a4.data(), nullptr};
  softsim::app::AppInfo info;
  info.name = "mesher";
  const int code = softsim::app::run_app(5, argv, info, mesher_body);
  if (code != 0 && code != 2 && code != 3) std::abort();
  std::remove(out.c_str());
  return 0;
}
