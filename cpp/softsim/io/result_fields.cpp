#include "softsim/io/result_fields.hpp"

namespace softsim::io {

std::vector<double> read_nodal_displacements(const Artifact& result, int num_nodes, const std::string& mesh_name) {
  const JsonReader disp = result.payload().at("displacement");
  if (disp.size() != static_cast<std::size_t>(num_nodes))
    disp.fail("one displacement per mesh node (" + std::to_string(num_nodes) + ")" +
              (mesh_name.empty() ? "" : " of " + mesh_name));
  std::vector<double> u(3 * disp.size());
  for (std::size_t i = 0; i < disp.size(); ++i) {
    const JsonReader row = disp[i];
    if (!row.raw().is_array() || row.raw().size() != 3) row.fail("[ux, uy, uz]");
    for (std::size_t k = 0; k < 3; ++k) u[3 * i + k] = row[k].as_double();
  }
  return u;
}

}  // namespace softsim::io
