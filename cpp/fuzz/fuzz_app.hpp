#pragma once
// The fuzz targets' entry point is the executables' own: run_app (cpp/apps/common/app.hpp). The
// fuzzed bytes are written to a file and given as `--config FILE` (or as the input file a fixed
// config names), so every input takes the path of a real run: regular-file and size checks, the
// nesting bound, duplicate keys, the provenance copy, the output-conflict scan, the strict
// readers, the run's memory and work estimates, the checks of what is built, the atomic write at
// --out and the clean-up of a failed run. Any input must end in exit 0, 2 or 3; exit 1 (an
// internal error, std::bad_alloc included), a crash, a hang or undefined behaviour is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <unistd.h>

#include "common/app.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/io/mesher_config.hpp"
#include "softsim/mesh/quality.hpp"

namespace fuzz {

// A file of this fuzzing process, /tmp/softsim-fuzz-PID-name, removed when the process exits.
inline std::string scratch(const std::string& name) {
  static std::set<std::string>* names = [] {
    static std::set<std::string> all;
    std::atexit([] {
      for (const std::string& n : all) std::remove(n.c_str());
    });
    return &all;
  }();
  const std::string path = "/tmp/softsim-fuzz-" + std::to_string(::getpid()) + "-" + name;
  names->insert(path);
  return path;
}

inline std::string write_scratch(const std::string& name, const void* data, std::size_t size) {
  const std::string path = scratch(name);
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

// Runs TOOL [MODE] --config CONFIG --out OUT through run_app with `body`, with `config_text` as
// the config file; aborts (a finding) on any exit code but 0, 2 and 3.
inline void run_tool(const std::string& tool, const std::string& config_text,
                     const std::function<void(softsim::app::AppContext&)>& body, const std::string& mode = "") {
  const std::string config = write_scratch("config.json", config_text.data(), config_text.size());
  const std::string out = scratch("out.json");
  std::vector<std::string> args = {tool};
  if (!mode.empty()) args.push_back(mode);
  for (const std::string& a : {std::string("--config"), config, std::string("--out"), out}) args.push_back(a);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  softsim::app::AppInfo info;
  info.name = tool;
  if (!mode.empty()) info.modes = {mode};
  const int code = softsim::app::run_app(static_cast<int>(args.size()), argv.data(), info, body);
  if (code != 0 && code != 2 && code != 3) std::abort();
  std::remove(out.c_str());
}

// mesher's body (cpp/apps/mesher.cpp) without the Gmsh surface import and the VTU (a path of the
// fuzzer's choosing is not written), for cuboids of at most 64 cells so each input stays quick.
inline void mesher_body(softsim::app::AppContext& ctx) {
  using namespace softsim;
  io::MesherConfig config = io::read_mesher_config(ctx.config());
  if (config.from_file) ctx.input(config.path);
  ctx.output(config.vtu, "/vtu");
  if (!config.from_file) {
    const auto& cells = config.cuboid.cells;
    if (static_cast<long long>(cells[0]) * cells[1] * cells[2] > 64) return;
  }
  const mesh::TetMesh m = io::build_mesh(config);
  nlohmann::json payload = io::mesher_payload(m, mesh::quality_report(m, config.sliver_threshold_deg), config.source);
  io::check_built_mesh(payload, ctx.config_path);
  ctx.write(io::kMeshSchema, io::kMeshSchemaVersion, std::move(payload));
}

// A mesh file of the fuzzer's bytes (extension `ext`: the reader mesher picks by it) imported by
// mesher as a real run would.
inline void run_mesher_on_file(const std::uint8_t* data, std::size_t size, const std::string& ext) {
  const std::string mesh = write_scratch("mesh" + ext, data, size);
  const nlohmann::json config = {{"source", {{"kind", "file"}, {"path", mesh}}}};
  run_tool("mesher", config.dump(), mesher_body);
}

}  // namespace fuzz
