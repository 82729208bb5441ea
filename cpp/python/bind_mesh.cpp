// softsim.Mesh and the ways to make one: the paper's cuboid, a file mesher imports or a tet_mesh
// artifact, or a whole mesher config. Every path goes through mesher's own config reader
// (io/mesher_config.hpp), so the Python API accepts and refuses exactly what mesher does.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "config_source.hpp"
#include "json_convert.hpp"
#include "py_mesh.hpp"
#include "softsim/io/artifact.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/io/mesher_config.hpp"
#include "softsim/io/output_guard.hpp"
#include "softsim/io/sha256.hpp"
#include "softsim/meshing/gmsh_volume.hpp"

namespace py = pybind11;

namespace softsim::python {

namespace {

// The arrays are viewed in place: nodes, tets and triangles are plain rows of numbers.
static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "nodes must be N x 3 contiguous doubles");
static_assert(sizeof(mesh::Tet) == 4 * sizeof(std::int32_t), "tets must be M x 4 contiguous int32");
static_assert(sizeof(mesh::Triangle) == 3 * sizeof(std::int32_t), "triangles must be K x 3 contiguous int32");

// A read-only NumPy view of `data` that keeps `owner` alive (a PyMesh never changes its arrays).
template <class T>
py::array view(const py::handle& owner, const T* data, std::vector<py::ssize_t> shape) {
  py::array a(py::dtype::of<T>(), std::move(shape), data, owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

py::dict index_views(const py::handle& owner, const std::map<std::string, std::vector<int>>& lists) {
  py::dict out;
  for (const auto& [name, list] : lists)
    out[py::str(name)] = view<std::int32_t>(owner, list.data(), {static_cast<py::ssize_t>(list.size())});
  return out;
}

std::shared_ptr<PyMesh> from_mesher_config(const Config& config) {
  return released(config.source(), [&] {
    io::MesherConfig mc = io::read_mesher_config(config.reader());
    mc.file.surface_mesher = meshing::volume_from_surface;  // .obj/.stl as mesher meshes them
    io::Provenance provenance;
    provenance.tool = "mesher";  // the artifact is mesher's, byte for byte
    provenance.config = config.json();
    if (mc.from_file) provenance.input_sha256[mc.path] = io::sha256_file(mc.path);
    // mesher's checks (app.cpp, apps/mesher.cpp): the VTU is no input, the mesh passes the readers.
    const io::ScopedInputGuard inputs({config.source(), mc.from_file ? mc.path : std::string()});
    if (!mc.vtu.empty()) io::check_output_path(mc.vtu, config.source() + ": /vtu");
    auto out = std::make_shared<PyMesh>();
    out->mesh = io::build_mesh(mc);
    io::check_built_mesh(io::mesher_payload(out->mesh, mesh::quality_report(out->mesh, mc.sliver_threshold_deg), mc.source),
                         config.source());
    if (!mc.vtu.empty()) io::write_mesher_vtu(mc.vtu, out->mesh, mc.vtu_format);
    out->sliver_threshold_deg = mc.sliver_threshold_deg;
    out->source = mc.source;
    out->provenance = io::provenance_json(provenance);
    return out;
  });
}

std::shared_ptr<PyMesh> from_artifact(const std::string& path) {
  return released(path, [&] {
    const io::Artifact a = io::Artifact::read(path, io::kMeshSchema, io::kMeshSchemaVersion);
    auto out = std::make_shared<PyMesh>();
    const io::JsonReader payload = a.payload();
    out->mesh = io::mesh_from_json(payload);
    if (const auto quality = payload.optional("quality"))
      out->sliver_threshold_deg = quality->get_positive("sliver_threshold_deg", out->sliver_threshold_deg);
    if (payload.has("source")) out->source = payload.at("source").raw();
    out->provenance = a.document().at("provenance");
    return out;
  });
}

double sliver_angle(const py::object& value, const std::string& where) {
  const double t = value.cast<double>();
  if (!(t > 0)) throw InputError(where + ": sliver_threshold_deg: expected a positive angle in degrees");
  return t;
}

bool is_json_path(const std::string& path) {
  return path.size() >= 5 && path.compare(path.size() - 5, 5, ".json") == 0;
}

std::shared_ptr<PyMesh> load(const std::filesystem::path& file, const py::object& scale, const py::object& target_edge,
                             const py::object& sliver_threshold_deg) {
  const std::string path = file.string();
  const std::string name = "softsim.load_mesh()";
  if (is_json_path(path)) {
    if (!scale.is_none() || !target_edge.is_none())
      throw InputError(path + ": expected no scale or target_edge for a tet_mesh artifact (its nodes are in metres "
                              "already); they apply to .msh, .vtk, .obj and .stl files");
    auto out = from_artifact(path);
    if (!sliver_threshold_deg.is_none()) out->sliver_threshold_deg = sliver_angle(sliver_threshold_deg, name);
    return out;
  }
  nlohmann::json source = {{"kind", "file"}, {"path", path}};
  if (!scale.is_none()) source["scale"] = to_json(scale, name);
  if (!target_edge.is_none()) source["target_edge"] = to_json(target_edge, name);
  nlohmann::json cfg = {{"source", source}};
  if (!sliver_threshold_deg.is_none()) cfg["sliver_threshold_deg"] = to_json(sliver_threshold_deg, name);
  return from_mesher_config(Config::from_json(std::move(cfg), name));
}

std::shared_ptr<PyMesh> cuboid(const py::object& cells, const py::object& size, const py::object& origin,
                               const py::object& sliver_threshold_deg) {
  const std::string name = "softsim.cuboid()";
  nlohmann::json source = {{"kind", "cuboid"}, {"cells", to_json(cells, name)}, {"size", to_json(size, name)}};
  if (!origin.is_none()) source["origin"] = to_json(origin, name);
  nlohmann::json cfg = {{"source", source}};
  if (!sliver_threshold_deg.is_none()) cfg["sliver_threshold_deg"] = to_json(sliver_threshold_deg, name);
  return from_mesher_config(Config::from_json(std::move(cfg), name));
}

void save(const PyMesh& m, const std::filesystem::path& path) {
  py::gil_scoped_release release;
  const mesh::QualityReport q = mesh::quality_report(m.mesh, m.sliver_threshold_deg);
  nlohmann::json payload = io::mesher_payload(m.mesh, q, m.source);
  if (m.source.is_null()) payload.erase("source");  // an artifact that recorded none
  io::write_artifact(path.string(), io::kMeshSchema, io::kMeshSchemaVersion, m.provenance, std::move(payload));
}

}  // namespace

void bind_mesh(py::module_& m) {
  py::class_<PyMesh, std::shared_ptr<PyMesh>>(m, "Mesh", R"doc(
A tetrahedral mesh (coordinates in metres), as mesher builds or imports it.

Make one with softsim.cuboid, softsim.load_mesh or softsim.mesh_from_config. A Mesh does not
change once made; its arrays are read-only NumPy views into it (no copy), valid for as long as
any of them or the Mesh is referenced.
)doc")
      .def_property_readonly(
          "nodes",
          [](py::object self) {
            const auto& mesh = self.cast<const PyMesh&>().mesh;
            return view<double>(self, mesh.nodes.data()->data(), {mesh.num_nodes(), 3});
          },
          "Node coordinates, N x 3 float64 (m).")
      .def_property_readonly(
          "tets",
          [](py::object self) {
            const auto& mesh = self.cast<const PyMesh&>().mesh;
            return view<std::int32_t>(self, mesh.tets.data()->data(), {mesh.num_tets(), 4});
          },
          "Tetrahedra, M x 4 int32 node indices, positively oriented: det[x1-x0, x2-x0, x3-x0] > 0.")
      .def_property_readonly(
          "boundary",
          [](py::object self) {
            const auto& mesh = self.cast<const PyMesh&>().mesh;
            return view<std::int32_t>(self, mesh.boundary.empty() ? nullptr : mesh.boundary.data()->data(),
                                      {static_cast<py::ssize_t>(mesh.boundary.size()), 3});
          },
          "Boundary triangles, K x 3 int32 node indices, counter-clockwise seen from outside.")
      .def_property_readonly(
          "node_sets", [](py::object self) { return index_views(self, self.cast<const PyMesh&>().mesh.node_sets); },
          "Named node sets: name -> sorted int32 node indices (cuboid: bottom, top, x_min, x_max, y_min, y_max,\n"
          "sides, boundary; imports: boundary). A new dict of views on each access.")
      .def_property_readonly(
          "element_tags",
          [](py::object self) { return index_views(self, self.cast<const PyMesh&>().mesh.element_tags); },
          "Per-element integer tags: name -> int32 array of length M (cuboid: layer, region; Gmsh: physical,\n"
          "region; VTK: its integer cell scalars).")
      .def_property_readonly("num_nodes", [](const PyMesh& p) { return p.mesh.num_nodes(); })
      .def_property_readonly("num_tets", [](const PyMesh& p) { return p.mesh.num_tets(); })
      .def_property_readonly(
          "sliver_threshold_deg", [](const PyMesh& p) { return p.sliver_threshold_deg; },
          "Smallest dihedral angle (degrees) below which the saved quality report flags an element.")
      .def_property_readonly(
          "source", [](const PyMesh& p) { return from_json(p.source); },
          "Where the mesh came from (the artifact's \"source\"): a dict, or None when not recorded.")
      .def_property_readonly(
          "provenance", [](const PyMesh& p) { return from_json(p.provenance); },
          "The provenance save() writes: mesher's for a mesh built here, the artifact's own for a loaded one.")
      .def(
          "quality",
          [](const PyMesh& p, const py::object& threshold) {
            const double t = threshold.is_none() ? p.sliver_threshold_deg : sliver_angle(threshold, "Mesh.quality()");
            nlohmann::json q;
            {
              py::gil_scoped_release release;
              q = io::quality_to_json(mesh::quality_report(p.mesh, t));
            }
            return from_json(q);
          },
          py::arg("sliver_threshold_deg") = py::none(),
          "The quality report of the artifact: counts, volume and dihedral ranges, the minimum altitude\n"
          "(the explicit stability length) and the slivers (default threshold: sliver_threshold_deg).")
      .def("save", &save, py::arg("path"),
           "Writes the tet_mesh artifact, exactly as mesher writes it for the same config.")
      .def(
          "save_vtu",
          [](const PyMesh& p, const std::filesystem::path& path) {
            py::gil_scoped_release release;
            io::write_mesher_vtu(path.string(), p.mesh);
          },
          py::arg("path"), "Writes the mesh as a ParaView .vtu file with its element tags as cell data (mesher's \"vtu\").")
      .def("__repr__", [](const PyMesh& p) {
        return "<softsim.Mesh: " + std::to_string(p.mesh.num_nodes()) + " nodes, " + std::to_string(p.mesh.num_tets()) +
               " tets>";
      });

  m.def("cuboid", &cuboid, py::arg("cells"), py::arg("size"), py::arg("origin") = py::none(),
        py::arg("sliver_threshold_deg") = py::none(), R"doc(
The paper's structured cuboid (000 §2.2.1): nx x ny x nz hexahedral cells of 5 tetrahedra each.

cells: (nx, ny, nz), 1 to 400 each; size: (lx, ly, lz) edge lengths of the whole box (m);
origin: lower corner (default 0). Node (i, j, k) has index i + (nx+1)(j + (ny+1)k). The same as
mesher with {"source": {"kind": "cuboid", "cells": ..., "size": ..., "origin": ...}}.
Raises InputError for values mesher refuses.
)doc");
  m.def("load_mesh", &load, py::arg("path"), py::arg("scale") = py::none(), py::arg("target_edge") = py::none(),
        py::arg("sliver_threshold_deg") = py::none(), R"doc(
Loads a mesh: a tet_mesh artifact (.json), or a file mesher imports: Gmsh .msh, legacy VTK .vtk,
or a closed .obj / .stl surface that Gmsh fills with tetrahedra.

scale: factor to metres for imported files (cm -> 0.01); target_edge: Gmsh's maximum element size
for surface meshing (file units). Raises InputError naming the file (and line or JSON pointer).
)doc");
  m.def(
      "mesh_from_config", [](const py::object& config) { return from_mesher_config(Config::from_python(config)); },
      py::arg("config"), R"doc(
Builds the mesh of a mesher config (a dict, or the path of a JSON file; see cpp/apps/mesher.md):
{"source": {"kind": "cuboid", ...} | {"kind": "file", ...}, "sliver_threshold_deg": 5, "vtu": ...}.
A "vtu" path is written as mesher writes it. Mesh.save then writes mesher's artifact.
)doc");
}

}  // namespace softsim::python
