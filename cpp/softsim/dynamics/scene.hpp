#pragma once
// What acts on the body: displacement constraints on node sets (fixed or prescribed with a
// ramp, per component), nodal forces, gravity, and a probe coupled to one node by a linear
// spring (000 eq. 26's R_v, plus the haptic probe of paper 001). Node lists are already
// resolved (see node_selection.hpp); everything is SI.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/mesh/closed_surface.hpp"

namespace softsim::dynamics {

// A load factor that goes from 0 to 1 over `duration` seconds and stays at 1. A zero duration
// means the full value from the start (t ≤ 0 included).
struct Ramp {
  enum class Shape { linear, smooth };  // smooth: 3s² − 2s³ (zero rate at both ends)
  double duration = 0;
  Shape shape = Shape::linear;
  double at(double t) const;
};

struct DisplacementConstraint {
  std::string name;  // for the reaction report ("bottom", "fixed[0]", ...)
  std::vector<int> nodes;
  std::array<bool, 3> components = {true, true, true};
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  // value at the end of the ramp (m)
  Ramp ramp;
};

struct NodalLoad {
  std::string name;
  std::vector<int> nodes;
  Eigen::Vector3d force_per_node = Eigen::Vector3d::Zero();  // N
  Ramp ramp;
};

// A tool tip at X_node + displacement × ramp(t), pulling the node through a spring:
// force on the node = stiffness × (tip − x_node).
struct ProbeSpring {
  int node = -1;
  double stiffness = 0;                                    // N/m
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();  // of the tip, relative to X_node (m)
  Ramp ramp;
  // The tip relative to X_node at time t. Rounded once, as a position (out of line, so the
  // compiler cannot fuse it into the spring law): a tip set between steps to the same value
  // gives the same forces, bit for bit.
  Eigen::Vector3d tip_displacement(double t) const;
};

// A rigid tool in frictionless contact with the body (issue 23): a sphere, a capsule (a probe,
// or a blade's back), a plane or a closed triangle mesh (any instrument), moved rigidly by `travel` × ramp(t) from where it starts, or
// set between steps (the haptic loop's probe position). Contact is kinematic: after each
// central-difference step a listed node that lies inside the tool is moved to the tool's surface
// along the normal (the projection an explicit TLED code such as NiftySim applies), and the
// force that move needs, M Δu / A (the central-difference coefficient of the node), is the
// contact force. A projection adds no stiffness, so the stable step is the body's own. With a
// friction coefficient μ, the node's motion along the surface relative to the tool is undone as
// well (stick) unless the force that takes exceeds μ times the normal force, when it is capped
// there (slip): Coulomb friction in the same kinematic form.
struct RigidTool {
  enum class Shape { sphere, capsule, plane, mesh };
  std::string name;
  Shape shape = Shape::sphere;
  double radius = 0;                                   // sphere, capsule (m)
  Eigen::Vector3d half_axis = Eigen::Vector3d::Zero();  // capsule: from its centre to one end of its segment (m)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();    // plane: unit normal pointing out of the tool, into the body
  Eigen::Vector3d start = Eigen::Vector3d::Zero();      // centre (plane: a point on it) at t = 0 (m)
  Eigen::Vector3d travel = Eigen::Vector3d::Zero();     // moved by travel × ramp(t) (m)
  Ramp ramp;
  double friction = 0;                        // Coulomb coefficient μ (0: frictionless)
  std::vector<int> nodes;                     // the nodes it can touch (a surface), ascending
  std::vector<Eigen::Vector3d> positions;     // their reference positions X (m)
  // mesh: a closed triangle surface in the tool's frame, placed at centre(t) (an instrument of
  // any shape; mesh/closed_surface.hpp). Shared: copies of a scene share one surface.
  std::shared_ptr<const mesh::ClosedSurface> surface;
  // Broad phase (dynamics/contact_search.hpp): how far nodes and the tool may move before the
  // candidate nodes are searched again (m); 0: a quarter of the tool's size.
  double search_margin = 0;

  Eigen::Vector3d centre(double t) const { return start + ramp.at(t) * travel; }
  // Signed distance of x from the surface of the tool at `centre` (negative inside), and the
  // unit normal pointing out of the tool at the nearest surface point.
  double signed_distance(const Eigen::Vector3d& x, const Eigen::Vector3d& centre, Eigen::Vector3d& normal) const;
  // The tool's bounding box at `centre`; false for a plane (unbounded).
  bool bounds(const Eigen::Vector3d& centre, Eigen::Vector3d& lo, Eigen::Vector3d& hi) const;
};

struct Scene {
  std::vector<DisplacementConstraint> constraints;  // later entries override earlier ones per component
  std::vector<NodalLoad> loads;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  // m/s², at the end of gravity_ramp
  // Gravity acts as gravity × gravity_ramp.at(t) (explicit runs; a static run scales every load
  // with its increments). No ramp (duration 0): constant from t = 0.
  Ramp gravity_ramp;
  bool has_probe = false;
  ProbeSpring probe;
  std::vector<RigidTool> tools;
};

// One constrained degree of freedom: the last constraint naming (node, component) wins.
struct ConstrainedDof {
  int node = 0;
  int component = 0;
  int constraint = 0;  // index into Scene::constraints
  double value = 0;    // final prescribed displacement (m)
};
// Sorted by (node, component). Throws InputError for a node index out of range.
std::vector<ConstrainedDof> resolve_constraints(const Scene& scene, int num_nodes);

// Per-dof flag: true where a constraint acts.
std::vector<char> constrained_mask(const std::vector<ConstrainedDof>& dofs, int num_nodes);

}  // namespace softsim::dynamics
