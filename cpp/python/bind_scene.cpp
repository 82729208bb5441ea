// softsim.Scene: the step-by-step explicit engine (hybrid::DhdScene) from Python. The loop a
// researcher writes around a simulation - move the tool, step, read the force, repeat - with the
// same config dhd_sim reads and the same engine it runs (a Scene stepped n times equals dhd_sim's
// run of n steps, bit for bit). Steps run with the GIL released.
#include <cstring>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "config_source.hpp"
#include "json_convert.hpp"
#include "py_arrays.hpp"
#include "py_mesh.hpp"
#include "softsim/hybrid/dhd_run.hpp"
#include "softsim/hybrid/dhd_scene.hpp"
#include "softsim/io/mesh_artifact.hpp"

namespace py = pybind11;

namespace softsim::python {

namespace {

std::unique_ptr<hybrid::DhdScene> make_scene(const py::object& config_value, const std::shared_ptr<PyMesh>& given) {
  Config config = Config::from_python(config_value);
  if (given && config.json().is_object() && !config.json().contains("mesh")) config.json()["mesh"] = kMeshObject;
  return released(config.source(), [&] {
    const io::JsonReader cfg = config.reader();
    // The scene shares the Mesh object's mesh (aliasing the PyMesh's ownership), or owns the
    // artifact the config names.
    std::shared_ptr<const mesh::TetMesh> mesh =
        given ? std::shared_ptr<const mesh::TetMesh>(given, &given->mesh)
              : std::make_shared<const mesh::TetMesh>(io::read_mesh_artifact(hybrid::read_mesh_path(cfg)));
    hybrid::DhdConfig c = hybrid::read_dhd_config(cfg, *mesh);
    return std::make_unique<hybrid::DhdScene>(mesh, std::move(c));
  });
}

int constraint_of(const hybrid::DhdScene& s, const py::object& which) {
  if (py::isinstance<py::str>(which)) return s.constraint_index(which.cast<std::string>());
  return which.cast<int>();
}

py::dict energies(const hybrid::DhdScene& s) {
  const auto& e = s.energies();
  std::vector<double> time, kinetic, strain, work, dissipated;
  for (const auto& x : e) {
    time.push_back(x.time);
    kinetic.push_back(x.kinetic);
    strain.push_back(x.strain);
    work.push_back(x.external_work);
    dissipated.push_back(x.dissipated);
  }
  py::dict d;
  d["time"] = py::array_t<double>(time.size(), time.data());
  d["kinetic"] = py::array_t<double>(kinetic.size(), kinetic.data());
  d["strain"] = py::array_t<double>(strain.size(), strain.data());
  d["external_work"] = py::array_t<double>(work.size(), work.data());
  d["dissipated"] = py::array_t<double>(dissipated.size(), dissipated.data());
  return d;
}

}  // namespace

void bind_scene(py::module_& m) {
  // The element kinds (fem::kElementKinds) as the dhd_result artifact's legend: entry k names
  // element_kind value k.
  m.attr("ELEMENT_KIND_LEGEND") = from_json(hybrid::element_kind_legend());
  static const std::string element_kind_doc = "Kind of each element: " + fem::kind_legend_text() +
                                              " (softsim.ELEMENT_KIND_LEGEND, the dhd_result artifact's "
                                              "element_kind_legend).";
  using hybrid::DhdScene;
  py::class_<DhdScene>(m, "Scene", R"doc(
A dhd_sim scene stepped from Python: Scene(config, mesh=None).

config: the dhd_sim config (cpp/apps/dhd_sim.md) as a dict (named "<dict>" in messages) or the
path of a JSON file; its solver must be explicit to step. mesh: a softsim.Mesh, or None to load
the tet_mesh artifact the config's "mesh" names.

Between step() calls, move the tool (set_probe_position, set_prescribed_displacement) and read
the state (displacement, velocity, reactions, probe_force, energies). Stepping n times in any
pieces equals dhd_sim's run of n steps bit for bit; "solver.steps" only marks where dhd_sim
stops (and takes a last energy sample), stepping may go on past it. The GIL is released while
stepping, so other Python threads run; one Scene must not be used by two threads at once.
Raises InputError (bad config or input, dhd_sim's exit 2) and NumericalError (instability,
inverted element: exit 3; the scene must then be reset()).
)doc")
      .def(py::init(&make_scene), py::arg("config"), py::arg("mesh") = py::none())
      .def(
          "step",
          [](DhdScene& s, int n) {
            py::gil_scoped_release release;
            s.step(n);
          },
          py::arg("n") = 1, "Advance n central-difference steps (000 eq. 33) with the GIL released.")
      .def("reset", &DhdScene::reset, "Back to t = 0: the initial state and the scene as configured.")
      .def_property_readonly("time", &DhdScene::time, "Simulated time (s).")
      .def_property_readonly("steps_done", &DhdScene::steps_done, "Steps since t = 0.")
      .def_property_readonly("dt", &DhdScene::dt, "The time step (s): the config's dt, or safety_factor x critical.")
      .def_property_readonly(
          "critical_dt", [](const DhdScene& s) { return s.critical_step().dt; }, "The critical step Le/c (000 eq. 34).")
      .def_property_readonly("num_nodes", &DhdScene::num_nodes)
      .def_property_readonly(
          "element_kind",
          [](const DhdScene& s) {
            std::vector<int> k;
            for (const fem::ElementKind kind : s.kinds()) k.push_back(static_cast<int>(kind));
            return py::array_t<int>(k.size(), k.data());
          },
          element_kind_doc.c_str())
      .def(
          "displacement",
          [](py::object self, bool copy) -> py::array {
            const DhdScene& s = self.cast<const DhdScene&>();
            const py::ssize_t n = s.num_nodes();
            if (copy) return rows3(s.displacement(), n);
            // In place: the engine's current buffer, read-only, valid until the next step() or
            // reset() (the engine rotates three buffers; the view then shows an older state).
            py::array a(py::dtype::of<double>(), {n, py::ssize_t{3}}, s.displacement(), self);
            a.attr("setflags")(py::arg("write") = false);
            return a;
          },
          py::arg("copy") = true, R"doc(
Displacement of every node, N x 3 (m). copy=False returns a read-only view of the engine's
buffer without copying: valid only until the next step() or reset().)doc")
      .def(
          "velocity",
          [](const DhdScene& s) {
            py::array_t<double> a({py::ssize_t{s.num_nodes()}, py::ssize_t{3}});
            s.velocity(a.mutable_data());
            return a;
          },
          "Velocity of every node, N x 3 (m/s): (u(t) - u(t - dt)) / dt.")
      .def(
          "reactions",
          [](DhdScene& s) {
            std::vector<Eigen::Vector3d> r;
            {
              py::gil_scoped_release release;
              r = s.reactions();
            }
            py::dict d;
            for (std::size_t c = 0; c < r.size(); ++c)
              d[py::str(s.config().scene.constraints[c].name)] = rows3(r[c].data(), 1).attr("reshape")(3);
            return d;
          },
          "Reaction of each constraint by name (N): F_int - R summed over its dofs, inertia left out.")
      .def("probe_force", &DhdScene::probe_force,
           "The probe spring's force on its node now, k (tip - x_node) (N); zeros without a probe.")
      .def_property("probe_position", &DhdScene::probe_position, &DhdScene::set_probe_position,
                    "World position of the probe's tip (m); set it between steps to move the tool.")
      .def("set_probe_position", &DhdScene::set_probe_position, py::arg("x"),
           "Put the probe's tip at world position x (m) from the next step on.")
      .def(
          "set_prescribed_displacement",
          [](DhdScene& s, const py::object& which, const Eigen::Vector3d& value) {
            s.set_prescribed_displacement(constraint_of(s, which), value);
          },
          py::arg("constraint"), py::arg("value"), R"doc(
Hold a constraint (its name, e.g. "prescribed top", or index) at displacement value (m) from the
next step on; its ramp is dropped.)doc")
      .def("constraint_names",
           [](const DhdScene& s) {
             std::vector<std::string> names;
             for (const auto& c : s.config().scene.constraints) names.push_back(c.name);
             return names;
           })
      .def("energies", &energies,
           "Energy samples since t = 0 as arrays: time, kinetic, strain, external_work, dissipated (J).")
      .def("__repr__", [](const DhdScene& s) {
        return "<softsim.Scene: " + std::to_string(s.num_nodes()) + " nodes, t = " + std::to_string(s.time()) + " s>";
      });
}

}  // namespace softsim::python
