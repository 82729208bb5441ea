#pragma once
// What the haptic loop drives (001 §3): a model advanced one haptic frame at a time by the
// spring force on its contact node. The whole model, the asynchronous regions and the exact
// reference all implement it, so one loop produces all three force signals.
#include <Eigen/Core>

namespace softsim::multirate {

class FrameStepper {
 public:
  virtual ~FrameStepper() = default;
  // Back to the undeformed state at rest, time zero.
  virtual void reset() = 0;
  // One haptic frame with `contact_force` (one entry per DOF of the contact node) held
  // constant over the frame.
  virtual void advance(const Eigen::VectorXd& contact_force) = 0;
  // Displacement of the contact node's DOF d after the last frame.
  virtual double contact_displacement(int d) const = 0;
  virtual int dofs_per_node() const = 0;
  // Nodes solved in the last frame at the haptic rate (the primary region); the whole model
  // and the reference report every free node.
  virtual int primary_nodes() const = 0;
};

}  // namespace softsim::multirate
