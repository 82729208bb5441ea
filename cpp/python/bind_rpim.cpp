// rpim_precompute from Python: the same config and modes (meshless::run_rpim_mode), returning
// the payload the executable writes.
#include "bindings.hpp"
#include "config_source.hpp"
#include "json_convert.hpp"
#include "softsim/io/artifact.hpp"
#include "softsim/meshless/rpim_modes.hpp"

namespace py = pybind11;

namespace softsim::python {

void bind_rpim(py::module_& m) {
  m.def(
      "rpim_precompute",
      [](const py::object& config_value, const std::string& mode) {
        const Config config = Config::from_python(config_value);
        const nlohmann::json payload = released(config.source(), [&] {
          meshless::RpimOutput out = meshless::run_rpim_mode(mode, config.reader());
          // rpim_precompute refuses to write a non-finite payload: the same failure here.
          io::require_finite(out.payload, out.schema + " payload");
          return std::move(out.payload);
        });
        return from_json(payload);
      },
      py::arg("config"), py::arg("mode") = meshless::kRpimModes.front(), R"doc(
The RPIM meshless plate model of paper 002 (rpim_precompute; see cpp/apps/rpim_precompute.md).

config: the rpim_precompute config as a dict (named "<dict>" in messages) or the path of a JSON
file. mode: "dataset" (solve a force set at the loaded node: the rpim_dataset payload),
"stability" (vary one RPIM parameter at a time: rpim_stability) or "convergence" (refine a block
with a manufactured solution: rpim_convergence).

Returns the payload dict rpim_precompute writes for the same config and mode. Raises InputError
or NumericalError (a singular moment matrix or stiffness). The GIL is released during the run.
)doc");
}

}  // namespace softsim::python
