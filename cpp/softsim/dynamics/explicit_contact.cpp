// Rigid tools in frictionless kinematic contact with the body (Scene::tools, issue 23).
//
// After the central-difference update of every node (000 eq. 33), each node a tool lists and
// its broad phase finds near it (contact_search.hpp) is moved out of every tool it entered, to
// the nearest point of the tool's surface at t + Δt. The move Δ is what a force f = Δ / A would have produced in eq. 33 (A = the node's coefficient of
// the force, Δt² / (m (1 + αΔt/2)) at a constant step), so f is the contact force on the node:
// for a tool held still it is exactly the reaction a displacement constraint on the node's normal
// component would report (ExplicitSolver::update_special's moving-constraint force), and the
// body's force on the tool is −Σ f. The work of f is booked trapezoidally like a nodal load's,
// so the energy balance holds and the growth check sees the tool's work as external work.
// A projection adds no stiffness: the stable step is the body's own (a penalty spring of
// stiffness k would lower it to 2 / sqrt((k_body + k) / m)). Coulomb friction (RigidTool::friction)
// takes the same kinematic form along the surface: the node's step relative to the tool is undone
// as far as a force of μ |f_n| allows.
// Nodes with a constrained component are not listed (a constraint wins); a node without mass
// (left without elements by a cut) holds its place and is not moved.
#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/io/errors.hpp"

namespace softsim::dynamics {

void ExplicitSolver::build_contacts(const std::vector<char>& constrained) {
  contact_begin_.assign(n_ + 1, 0);
  contacts_.clear();
  std::vector<std::vector<ContactEntry>> per_node(n_);
  for (std::size_t k = 0; k < scene_.tools.size(); ++k) {
    const RigidTool& tool = scene_.tools[k];
    if (tool.positions.size() != tool.nodes.size())
      throw std::invalid_argument("RigidTool: one reference position per node");
    if (tool.shape == RigidTool::Shape::mesh && !tool.surface)
      throw std::invalid_argument("RigidTool: a mesh tool needs its surface");
    for (std::size_t j = 0; j < tool.nodes.size(); ++j) {
      const int node = tool.nodes[j];
      if (node < 0 || node >= n_) throw InputError("tool \"" + tool.name + "\": node out of range");
      if (constrained[3 * node] || constrained[3 * node + 1] || constrained[3 * node + 2]) continue;
      per_node[node].push_back(ContactEntry{static_cast<int>(k), node, tool.positions[j]});
    }
  }
  for (int i = 0; i < n_; ++i) {
    contact_begin_[i + 1] = contact_begin_[i] + static_cast<int>(per_node[i].size());
    contacts_.insert(contacts_.end(), per_node[i].begin(), per_node[i].end());
  }
  contact_force_.assign(3 * contacts_.size(), 0.0);
  contact_work_.assign(contacts_.size(), 0.0);
  setup_contact_search();
}

// Per tool, its entries (ascending, so by node) for the broad phase.
void ExplicitSolver::setup_contact_search() {
  std::vector<std::vector<int>> entries(scene_.tools.size());
  std::vector<int> entry_node(contacts_.size());
  std::vector<Eigen::Vector3d> entry_position(contacts_.size());
  for (std::size_t e = 0; e < contacts_.size(); ++e) {
    entries[contacts_[e].tool].push_back(static_cast<int>(e));
    entry_node[e] = contacts_[e].node;
    entry_position[e] = contacts_[e].position;
  }
  search_.setup(scene_.tools, std::move(entries), entry_node, entry_position, opt_.contact_search);
}

// Tool by tool (a node touched by two tools leaves the first, then the second, as before the
// broad phase): each node is updated by then, and the next step reads u_{n+1} only after the
// barrier that follows.
void ExplicitSolver::contact_pass(int step, const double* up, const double* uc, double* un) {
  const StepSegment& seg = segments_.back();
  const double t = seg.time + (step - seg.first_step) * seg.dt;
  const double t_next = t + seg.dt;
  for (std::size_t k = 0; k < scene_.tools.size(); ++k) {
    const RigidTool& tool = scene_.tools[k];
    const Eigen::Vector3d centre = tool.centre(t_next);
    for (int e : search_.candidates(static_cast<int>(k), tool, centre, un, contact_force_.data())) {
      project_entry(e, tool, centre, step, t, up, uc, un);
      sample_trajectories(contacts_[e].node, step, un);
    }
  }
}

void ExplicitSolver::project_entry(int e, const RigidTool& tool, const Eigen::Vector3d& centre, int step, double t,
                                   const double* up, const double* uc, double* un) {
  const ContactEntry& c = contacts_[e];
  const int i = c.node;
  double* f = &contact_force_[3 * e];
  const double f_before[3] = {f[0], f[1], f[2]};
  f[0] = f[1] = f[2] = 0.0;
  if (A_[i] > 0) {
    const Eigen::Vector3d x = c.position + Eigen::Vector3d(un[3 * i], un[3 * i + 1], un[3 * i + 2]);
    Eigen::Vector3d normal;
    const double d = tool.signed_distance(x, centre, normal);
    if (d < 0) {
      for (int k = 0; k < 3; ++k) {
        const double move = -d * normal[k];
        un[3 * i + k] += move;
        f[k] = move / A_[i];
      }
      if (tool.friction > 0) {
        // The node's step relative to the tool, along the surface: undone (stick) unless the
        // force that takes exceeds μ |f_n| (slip: the force is capped there, along the same line).
        const Eigen::Vector3d centre_now = step == tool_moved_at_[c.tool] ? tool_moved_from_[c.tool] : tool.centre(t);
        Eigen::Vector3d slide(un[3 * i] - uc[3 * i], un[3 * i + 1] - uc[3 * i + 1], un[3 * i + 2] - uc[3 * i + 2]);
        slide -= centre - centre_now;
        slide -= slide.dot(normal) * normal;
        Eigen::Vector3d tangential = -slide / A_[i];
        const double limit = tool.friction * (-d / A_[i]);
        const double size = tangential.norm();
        if (size > limit) tangential *= limit / size;
        for (int k = 0; k < 3; ++k) {
          un[3 * i + k] += A_[i] * tangential[k];
          f[k] += tangential[k];
        }
      }
    }
  }
  if (step > 0) {
    double w = 0;
    for (int k = 0; k < 3; ++k) w += 0.5 * (f_before[k] + f[k]) * (uc[3 * i + k] - up[3 * i + k]);
    contact_work_[e] += w;
  }
}

void ExplicitSolver::set_tool_position(int k, const Eigen::Vector3d& centre) {
  if (k < 0 || k >= static_cast<int>(scene_.tools.size())) throw InputError("tool " + std::to_string(k) + " out of range");
  if (!centre.allFinite()) throw InputError("tool: a finite position");
  if (!started_) start();
  tool_moved_from_[k] = scene_.tools[k].centre(time());
  tool_moved_at_[k] = n_done_;
  scene_.tools[k].start = centre;
  scene_.tools[k].travel.setZero();
  scene_.tools[k].ramp = Ramp{};
}

Eigen::Vector3d ExplicitSolver::tool_force(int k) const {
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (std::size_t e = 0; e < contacts_.size(); ++e)
    if (contacts_[e].tool == k) total -= Eigen::Vector3d(contact_force_[3 * e], contact_force_[3 * e + 1], contact_force_[3 * e + 2]);
  return total;
}

int ExplicitSolver::tool_contacts(int k) const {
  int count = 0;
  for (std::size_t e = 0; e < contacts_.size(); ++e)
    if (contacts_[e].tool == k &&
        (contact_force_[3 * e] != 0 || contact_force_[3 * e + 1] != 0 || contact_force_[3 * e + 2] != 0))
      ++count;
  return count;
}

void ExplicitSolver::record_tool_forces() {
  for (std::size_t k = 0; k < scene_.tools.size(); ++k) {
    tool_force_samples_[k].push_back(tool_force(static_cast<int>(k)));
    tool_contact_samples_[k].push_back(tool_contacts(static_cast<int>(k)));
  }
}

}  // namespace softsim::dynamics
