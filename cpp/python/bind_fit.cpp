// The fits' real-time playback from Python: a fitted model (the "model" of a marquardt_fit
// artifact) played back at forces with fit::SurfacePlayer, and marquardt_fit's play mode
// (fit/surface_playback.hpp) returning the payload the executable writes.
#include <cmath>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "config_source.hpp"
#include "json_convert.hpp"
#include "softsim/fit/model_json.hpp"
#include "softsim/fit/playback.hpp"
#include "softsim/fit/surface_playback.hpp"
#include "softsim/io/artifact.hpp"

namespace py = pybind11;

namespace softsim::python {

namespace {

struct PyFitModel {
  explicit PyFitModel(fit::FitModel m) : model(std::move(m)), player(model) {}
  fit::FitModel model;
  fit::SurfacePlayer player;  // precomputed from `model` once
};

using Forces = py::array_t<double, py::array::c_style | py::array::forcecast>;

// One force (3,) or a batch (k, 3) of finite values: the count k, or -1 for a single force.
py::ssize_t batch_size(const Forces& forces, const std::string& where) {
  const bool single = forces.ndim() == 1 && forces.shape(0) == 3;
  if (!single && !(forces.ndim() == 2 && forces.shape(1) == 3)) {
    std::string shape;
    for (py::ssize_t d = 0; d < forces.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(forces.shape(d));
    throw InputError(where + ": expected a force [fx, fy, fz] or an array of shape (k, 3) in N, got shape (" + shape + ")");
  }
  for (py::ssize_t i = 0; i < forces.size(); ++i)
    if (!std::isfinite(forces.data()[i])) throw InputError(where + ": expected finite forces in N, got " + std::to_string(forces.data()[i]));
  return single ? -1 : forces.shape(0);
}

// Writes `per_force` values per force into a new array of shape (k,) + tail (or tail alone for
// a single force), calling fill(force, out) with the GIL released.
template <class Fill>
py::array_t<double> for_each_force(const Forces& forces, const std::string& where, std::vector<py::ssize_t> tail,
                                   py::ssize_t per_force, Fill fill) {
  const py::ssize_t k = batch_size(forces, where);
  std::vector<py::ssize_t> shape = tail;
  if (k >= 0) shape.insert(shape.begin(), k);
  py::array_t<double> out(shape);
  const double* in = forces.data();
  double* o = out.mutable_data();
  const py::ssize_t count = k >= 0 ? k : 1;
  py::gil_scoped_release release;
  for (py::ssize_t i = 0; i < count; ++i) fill(Eigen::Vector3d(in[3 * i], in[3 * i + 1], in[3 * i + 2]), o + i * per_force);
  return out;
}

}  // namespace

void bind_fit(py::module_& m) {
  py::class_<PyFitModel, std::shared_ptr<PyFitModel>>(m, "FitModel", R"doc(
A fitted surface model of paper 002 §3 (the "model" of a marquardt_fit artifact): force ->
loaded-node displacement (relation 1) -> surface coefficients (relation 3) -> the displacement of
every surface node (relation 2), summed over the load directions the model contains.
)doc")
      .def_static(
          "load",
          [](const std::filesystem::path& file) {
            const std::string path = file.string();
            return released(path, [&] { return std::make_shared<PyFitModel>(fit::read_fit_model(path)); });
          },
          py::arg("path"), "Reads the model of a marquardt_fit artifact (the file marquardt_fit fit writes).")
      .def_static(
          "from_dict",
          [](const py::dict& model) {
            const Config config = Config::from_python(model);
            return released(config.source(),
                            [&] { return std::make_shared<PyFitModel>(fit::model_from_json(config.reader())); });
          },
          py::arg("model"), "A model from the dict of an artifact's payload[\"model\"] (or FitModel.to_dict()).")
      .def("to_dict", [](const PyFitModel& f) { return from_json(fit::model_to_json(f.model)); },
           "The model as the artifact's payload[\"model\"] holds it.")
      .def_property_readonly(
          "nodes",
          [](py::object self) {
            const Eigen::MatrixXd& nodes = self.cast<const PyFitModel&>().model.nodes;
            const auto d = static_cast<py::ssize_t>(sizeof(double));
            py::array a(py::dtype::of<double>(), {nodes.rows(), Eigen::Index{3}}, {d, d * nodes.rows()}, nodes.data(), self);
            a.attr("setflags")(py::arg("write") = false);
            return a;
          },
          "The surface nodes, n x 3 (m): a read-only view, the rows of play()'s output.")
      .def_property_readonly("node_count", [](const PyFitModel& f) { return f.player.node_count(); })
      .def_property_readonly(
          "loaded_node_index", [](const PyFitModel& f) { return f.model.loaded_node; },
          "Row of nodes where the force acts (0-based; the artifact's \"loaded_node\" is this + 1).")
      .def_property_readonly(
          "directions",
          [](const PyFitModel& f) {
            std::vector<std::string> out;
            for (int d = 0; d < 3; ++d)
              if (f.model.directions[d].present) out.emplace_back(fit::kAxis[d]);
            return out;
          },
          "The load directions the model contains (\"x\", \"y\", \"z\"); force components along others play nothing.")
      .def(
          "play",
          [](const PyFitModel& f, const Forces& forces) {
            const py::ssize_t n = f.player.node_count();
            return for_each_force(forces, "FitModel.play()", {n, 3}, 3 * n,
                                  [&](const Eigen::Vector3d& force, double* out) { f.player.play(force, out); });
          },
          py::arg("forces"), R"doc(
Surface displacement for a force (fx, fy, fz) in N: n x 3 (m), the rows of nodes. For an array of
k forces (k x 3): k x n x 3. The real-time path (no allocation per force); GIL released.
)doc")
      .def(
          "loaded_displacement",
          [](const PyFitModel& f, const Forces& forces) {
            return for_each_force(forces, "FitModel.loaded_displacement()", {3}, 3,
                                  [&](const Eigen::Vector3d& force, double* out) {
                                    Eigen::Map<Eigen::Vector3d>{out} = f.player.loaded_displacement(force);
                                  });
          },
          py::arg("forces"),
          "Relation 1's loaded-node displacements (delta_x, delta_y, delta_z) in m for a force (3,) or forces (k, 3).")
      .def("__repr__", [](const PyFitModel& f) {
        return "<softsim.FitModel: " + std::to_string(f.player.node_count()) + " surface nodes>";
      });

  m.def(
      "play_fit",
      [](const py::object& config_value) {
        const Config config = Config::from_python(config_value);
        const nlohmann::json payload = released(config.source(), [&] {
          nlohmann::json p = fit::play_back(fit::read_playback_config(config.reader()));
          // marquardt_fit refuses to write a non-finite payload: the same failure here.
          io::require_finite(p, std::string(fit::kPlaybackSchema) + " payload");
          return p;
        });
        return from_json(payload);
      },
      py::arg("config"), R"doc(
marquardt_fit's play mode: {"fit": "fit.json", "forces": [[fx, fy, fz], ...], "reference":
"dataset.json" (optional)} as a dict or the path of a JSON file; returns the surface_playback
payload marquardt_fit writes (with a reference: its exact superposition and the errors).
)doc");
}

}  // namespace softsim::python
