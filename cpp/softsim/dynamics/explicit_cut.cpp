// Cut events of the explicit engine: element removal between steps, and the scheduled events
// (ExplicitOptions::event_times) that trigger them from a config.
#include <chrono>

#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/fem/element_response.hpp"
#include "softsim/fem/tet_geometry.hpp"
#include "softsim/io/errors.hpp"
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

double ExplicitSolver::split_nodes(const mesh::TetMesh& mesh, const std::vector<fem::ElementSet::NodeCopy>& copies) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!started_) start();
  for (const auto& c : copies) {
    if (c.node < 0 || c.node >= n_) throw std::invalid_argument("split_nodes: node out of range");
    if (dof_begin_[c.node] != dof_begin_[c.node + 1] || load_begin_[c.node] != load_begin_[c.node + 1] ||
        (scene_.has_probe && scene_.probe.node == c.node))
      throw InputError("cut: node " + std::to_string(c.node) + " carries a constraint, a load or the probe and cannot split");
  }
  elements_.split_nodes(mesh, copies);
  const double density = elements_.material().elastic.density;
  bool new_contacts = false;
  for (const auto& c : copies) {
    const int a = c.node, b = n_++;
    for (auto& buffer : buf_)
      for (int k = 0; k < 3; ++k) buffer.push_back(buffer[3 * a + k]);
    for (std::vector<double>* v : {&v_start_, &u0_, &v0_, &u_before_})
      if (!v->empty())
        for (int k = 0; k < 3; ++k) v->push_back((*v)[3 * a + k]);
    if (!applied_force_.empty()) applied_force_.insert(applied_force_.end(), 3, 0.0);
    constrained_.insert(constrained_.end(), 3, 0);
    double moved = 0;
    for (int e : c.elements) moved += 0.25 * density * mesh::signed_volume(mesh, mesh.tets[e]);  // as lumped_mass
    mass_.push_back(moved);
    mass_[a] -= moved;
    if (!elements_left_.empty()) {
      elements_left_.push_back(static_cast<int>(c.elements.size()));
      elements_left_[a] -= static_cast<int>(c.elements.size());
    }
    for (auto* v : {&A_, &B_, &C_, &Am_}) v->push_back(0.0);
    set_node_coefficients(a);
    set_node_coefficients(b);
    held_.push_back(0);
    for (auto* begin : {&dof_begin_, &load_begin_, &trajectory_begin_}) begin->push_back(begin->back());
    // The copy joins the tools its node is listed for (its entries follow the others: it has the
    // highest index, so the per-node list stays in node order).
    contact_begin_.push_back(contact_begin_.back());
    for (int e = contact_begin_[a]; e < contact_begin_[a + 1]; ++e) {
      ContactEntry entry = contacts_[e];
      entry.node = b;
      contacts_.push_back(entry);
      ++contact_begin_.back();
      new_contacts = true;
    }
    // The copy's forces are all written once every tile is done: it is updated after the barrier.
    deferred_nodes_.push_back(b);
    ++deferred_begin_.back();
  }
  pressure_nodes_.back() = n_;
  if (new_contacts) {
    contact_force_.resize(3 * contacts_.size(), 0.0);
    contact_work_.resize(contacts_.size(), 0.0);
    setup_contact_search();
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Calls the scheduled events whose time the run has reached (within round-off of the step).
void ExplicitSolver::fire_due_events() {
  while (next_event_ < opt_.event_times.size() && opt_.event_times[next_event_] - time() <= 1e-9 * dt()) {
    const int k = static_cast<int>(next_event_++);
    if (opt_.on_event) opt_.on_event(k);
  }
}

}  // namespace softsim::dynamics
