#pragma once
// What a softsim.Mesh holds: the mesh, and what its tet_mesh artifact carries besides the mesh
// (where it came from, the sliver threshold of its quality report, the provenance), so that
// Mesh.save writes the artifact mesher writes for the same config, and re-saving a loaded
// artifact keeps the provenance of the run that made it. Immutable once made: the NumPy views
// of its arrays stay valid for as long as the object lives.
#include <nlohmann/json.hpp>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::python {

struct PyMesh {
  mesh::TetMesh mesh;
  double sliver_threshold_deg = 5.0;
  nlohmann::json source;      // the payload's "source" (null: none recorded)
  nlohmann::json provenance;  // the envelope's "provenance"
};

}  // namespace softsim::python
