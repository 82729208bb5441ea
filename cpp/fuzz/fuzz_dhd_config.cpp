// libFuzzer target: the dhd_sim config reader (hybrid::read_dhd_config) on a fixed 27-node
// cuboid, then the partition, the step choice and a few steps of the configured solver.
// Any input must end in a result, an InputError or a NumericalError: never a crash, a hang,
// an out-of-range access, undefined behaviour or another exception type.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzz_json.hpp"
#include "softsim/hybrid/dhd_run.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/mesh/cuboid.hpp"

namespace {

const softsim::mesh::TetMesh& fuzz_mesh() {
  static const softsim::mesh::TetMesh mesh = [] {
    softsim::mesh::CuboidSpec spec;
    spec.cells = {2, 2, 2};
    spec.size = Eigen::Vector3d(0.02, 0.02, 0.02);
    return softsim::mesh::make_cuboid(spec);
  }();
  return mesh;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // The strain partition opens the file its config names; keep the fuzzer away from devices
  // that never end (/dev/zero) — a config naming one is not a parser bug.
  if (text.find("/dev") != std::string::npos || text.find("/proc") != std::string::npos) return 0;
  nlohmann::json doc;
  if (!parse_fuzz_json(data, size, doc)) return 0;
  if (!doc.is_object()) return 0;
  try {
    const softsim::io::JsonReader cfg(doc, "fuzz.json");
    softsim::hybrid::DhdConfig config = softsim::hybrid::read_dhd_config(cfg, fuzz_mesh());
    // Bounded work: the point is the code paths a config opens, not long runs.
    config.explicit_solver.steps = std::min(config.explicit_solver.steps, 4);
    config.explicit_solver.energy_interval = std::min(config.explicit_solver.energy_interval, 2);
    config.static_options.increments = std::min(config.static_options.increments, 2);
    config.static_options.max_iterations = std::min(config.static_options.max_iterations, 4);
    config.threads = 1;
    config.output.vtu.clear();
    config.output.vtu_interval = 0;
    softsim::hybrid::run_dhd(fuzz_mesh(), config, {});
  } catch (const softsim::InputError&) {
  } catch (const softsim::NumericalError&) {
  }
  return 0;
}
