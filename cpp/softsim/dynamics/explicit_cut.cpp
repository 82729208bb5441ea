// Cut events of the explicit engine: element removal between steps, and the scheduled events
// (ExplicitOptions::event_times) that trigger them from a config.
#include <chrono>

#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/fem/element_response.hpp"
#include "softsim/fem/tet_geometry.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::dynamics {

CutReport ExplicitSolver::remove_elements(const mesh::TetMesh& mesh, const std::vector<int>& elements) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!started_) start();
  if (mesh.num_nodes() != n_) throw std::invalid_argument("remove_elements: not the element set's mesh");
  if (elements_left_.empty()) {
    elements_left_.assign(n_, 0);
    for (int e = 0; e < mesh.num_tets(); ++e)
      if (!elements_.removed(e))
        for (int a : mesh.tets[e]) ++elements_left_[a];
  }
  CutReport report;
  // The energy the elements hold now (their element part: an ANP element's volumetric energy
  // lives at its nodes and is shared out again among the elements left there).
  const double* u = displacement();
  const double* before = buf_[n_done_ % 3].data();
  const double dt_before = step_size(n_done_ - 1);
  for (int e : elements) {
    if (e < 0 || e >= mesh.num_tets() || elements_.removed(e)) continue;
    report.strain_energy += fem::with_element_material(elements_.material(), e, [&](const fem::Material& m) {
      return fem::element_energy(m, elements_.kinds()[e], fem::tet_shape(mesh, e), fem::corner_displacements(mesh, e, u));
    });
  }
  report.elements = elements_.remove_elements(mesh, elements);
  const double density = elements_.material().elastic.density;
  std::vector<int> touched;
  for (int e : report.elements) {
    const double quarter = 0.25 * density * mesh::signed_volume(mesh, mesh.tets[e]);  // as lumped_mass
    report.mass += 4 * quarter;
    for (int a : mesh.tets[e]) {
      double v2 = 0;
      for (int k = 0; k < 3; ++k) {
        const double v = (u[3 * a + k] - before[3 * a + k]) / dt_before;
        v2 += v * v;
      }
      report.kinetic_energy += 0.5 * quarter * v2;
      mass_[a] -= quarter;
      if (--elements_left_[a] == 0) {
        mass_[a] = 0.0;  // exactly: no round-off mass left on a node without elements
        ++report.detached_nodes;
      }
      touched.push_back(a);
    }
  }
  for (int a : touched) set_node_coefficients(a);
  removed_energy_ += report.strain_energy + report.kinetic_energy;
  if (opt_.elements_removed && !report.elements.empty()) opt_.elements_removed(report.elements);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

// Calls the scheduled events whose time the run has reached (within round-off of the step).
void ExplicitSolver::fire_due_events() {
  while (next_event_ < opt_.event_times.size() && opt_.event_times[next_event_] - time() <= 1e-9 * dt()) {
    const int k = static_cast<int>(next_event_++);
    if (opt_.on_event) opt_.on_event(k);
  }
}

}  // namespace softsim::dynamics
