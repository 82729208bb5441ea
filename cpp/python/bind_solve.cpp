// dhd_sim from Python: the same config, read by the same strict reader (hybrid::read_dhd_config),
// the same run (hybrid::run_dhd_writing_vtu) and the same "dhd_result" payload
// (hybrid::result_payload), with the mesh given as a softsim.Mesh or named by the config.
#include <cstring>
#include <sstream>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "config_source.hpp"
#include "json_convert.hpp"
#include "py_arrays.hpp"
#include "py_mesh.hpp"
#include "softsim/hybrid/dhd_vtu.hpp"
#include "softsim/io/output_guard.hpp"
#include "softsim/io/artifact.hpp"
#include "softsim/io/mesh_artifact.hpp"

namespace py = pybind11;

namespace softsim::python {

namespace {

struct Outcome {
  hybrid::DhdRun run;
  nlohmann::json payload;
};

// A Mesh passed takes the place of the config's "mesh" path; without one, the config names the
// tet_mesh artifact, as for dhd_sim.
Outcome run(const std::shared_ptr<PyMesh>& given, Config& config, bool static_only) {
  if (given && config.json().is_object() && !config.json().contains("mesh")) config.json()["mesh"] = kMeshObject;
  return released(config.source(), [&] {
    const io::JsonReader cfg = config.reader();
    mesh::TetMesh loaded;
    if (!given) loaded = io::read_mesh_artifact(hybrid::read_mesh_path(cfg));
    const mesh::TetMesh& mesh = given ? given->mesh : loaded;
    const hybrid::DhdConfig c = hybrid::read_dhd_config(cfg, mesh);
    // dhd_sim's output rules (app.cpp): the VTU is none of the run's inputs.
    const io::ScopedInputGuard inputs({config.source(), given ? std::string() : hybrid::read_mesh_path(cfg)});
    if (!c.output.vtu.empty()) io::check_output_path(c.output.vtu, config.source() + ": /output/vtu");
    if (static_only && !c.static_solver)
      cfg.at("solver").at("kind").fail("\"static\" (solve_static solves the static equilibrium; run_dhd runs explicit dynamics)");
    Outcome out{hybrid::run_dhd_writing_vtu(mesh, c), nullptr};
    out.payload = hybrid::result_payload(mesh, c, out.run);
    // dhd_sim refuses to write a non-finite payload: the same failure here.
    io::require_finite(out.payload, std::string(hybrid::kResultSchema) + " payload");
    return out;
  });
}

// solve_static's default solver block: {"kind": "static"} (dhd_sim's default is explicit).
void default_to_static(nlohmann::json& config) {
  if (!config.is_object()) return;
  const auto solver = config.find("solver");
  if (solver == config.end())
    config["solver"] = {{"kind", "static"}};
  else if (solver->is_object() && !solver->contains("kind"))
    (*solver)["kind"] = "static";
}

struct StaticSolution {
  py::array_t<double> displacement;
  py::array_t<double> reactions;
  std::vector<std::string> reaction_names;
  std::vector<int> iterations;
  double residual = 0;
  double force_scale = 0;
  double strain_energy = 0;
  py::object probe_force = py::none();
  py::object payload;
};

StaticSolution solve_static(const std::shared_ptr<PyMesh>& mesh, const py::object& config_value) {
  Config config = Config::from_python(config_value);
  default_to_static(config.json());
  const Outcome out = run(mesh, config, true);
  const dynamics::StaticResult& r = *out.run.static_result;
  StaticSolution s;
  s.displacement = rows3(r.displacement.data(), r.displacement.size() / 3);
  s.reactions = rows3(r.reactions.empty() ? nullptr : r.reactions.front().data(), r.reactions.size());
  for (const auto& item : out.payload.at("reactions")) s.reaction_names.push_back(item.at("name").get<std::string>());
  s.iterations = r.iterations;
  s.residual = r.residual;
  s.force_scale = r.force_scale;
  s.strain_energy = r.strain_energy;
  if (out.payload.contains("probe")) s.probe_force = rows3(r.probe_force.data(), 1).attr("reshape")(3);
  s.payload = from_json(out.payload);
  return s;
}

}  // namespace

void bind_solve(py::module_& m) {
  py::class_<StaticSolution>(m, "StaticSolution", "The static equilibrium of a dhd_sim config (softsim.solve_static).")
      .def_readonly("displacement", &StaticSolution::displacement, "Displacement of every node, N x 3 (m).")
      .def_readonly("reactions", &StaticSolution::reactions,
                    "Reaction of each constraint, K x 3 (N): the sum of F_int - R over its constrained dofs.")
      .def_readonly("reaction_names", &StaticSolution::reaction_names,
                    "The constraints' names, in the order of reactions (\"fixed bottom\", \"prescribed top\", ...).")
      .def_readonly("iterations", &StaticSolution::iterations, "Newton iterations of each load increment.")
      .def_readonly("residual", &StaticSolution::residual, "Final largest residual force on a free dof (N).")
      .def_readonly("force_scale", &StaticSolution::force_scale, "The force scale the tolerance multiplies (N).")
      .def_readonly("strain_energy", &StaticSolution::strain_energy, "Strain energy at equilibrium (J).")
      .def_readonly("probe_force", &StaticSolution::probe_force,
                    "The probe spring's force on its node (3,) (N), or None without a probe.")
      .def_readonly("payload", &StaticSolution::payload,
                    "The whole dhd_result payload, as json.load reads the artifact dhd_sim writes.")
      .def("__repr__", [](const StaticSolution& s) {
        std::ostringstream out;
        out << "<softsim.StaticSolution: " << s.displacement.shape(0) << " nodes, residual " << s.residual << " N>";
        return out.str();
      });

  m.def("solve_static", &solve_static, py::arg("mesh").none(true), py::arg("config"), R"doc(
The static equilibrium (Newton, load increments) of a dhd_sim config; see cpp/apps/dhd_sim.md.

mesh: a softsim.Mesh, or None to load the tet_mesh artifact the config's "mesh" names. A Mesh
passed takes the place of that path (the key may then be left out).
config: the dhd_sim config as a dict (named "<dict>" in messages) or the path of a JSON file.
Without a solver block, or a solver block without "kind", the solver is {"kind": "static"};
an explicit solver.kind is an InputError. Output files the config names ("vtu") are written.

Returns a StaticSolution whose payload is what dhd_sim writes for the same config. Raises
InputError (what dhd_sim exits 2 on) or NumericalError (exit 3: Newton not converged, singular
tangent, inverted element). The GIL is released during the solve.
)doc");
  m.def(
      "run_dhd",
      [](const std::shared_ptr<PyMesh>& mesh, const py::object& config_value) {
        Config config = Config::from_python(config_value);
        return from_json(run(mesh, config, false).payload);
      },
      py::arg("mesh").none(true), py::arg("config"), R"doc(
One dhd_sim run, explicit dynamics or static equilibrium, as its config says; returns the whole
dhd_result payload as a dict (json.load of the artifact dhd_sim writes for the same config).

mesh and config as for solve_static (the solver defaults to explicit, as in dhd_sim). Raises
InputError or NumericalError (for example an explicit step forced above the critical step that
blows up). The GIL is released during the run; OpenMP threads as the config's "threads".
)doc");
}

}  // namespace softsim::python
