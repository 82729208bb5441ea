#pragma once
// What the device may be sent, whatever one sample or the model says. A haptic device renders
// the force it is commanded; a wrong sample (a tip 1 km away, millimetres sent as metres) or a
// model on its way to a numerical failure can ask for kilonewtons before any guard reacts. So
// every force, in `run` and in every answer of `serve`, goes through ForceLimiter:
//   - a force that is not finite is never sent: the device gets zero, and the limiter's history
//     restarts from zero;
//   - the magnitude is clamped to `max_force` (N), keeping the direction;
//   - the change from the previous frame's force is clamped to `max_force_step` (N per frame),
//     except a drop to exactly zero (contact released, a recovered failure): letting go is safe.
// Each clamp is counted and the first kListedClamps are listed (frame, force asked, force sent).
// Tip positions farther than `max_distance` from the organ's bounding box are refused before
// any force is computed (Workspace).
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::haptic {

struct DeviceSafetyConfig {
  double max_force = 20.0;      // N: above what desktop devices render (3-20 N), far below harm
  double max_force_step = 2.0;  // N per frame (2000 N/s at 1 kHz)
  double max_distance = 1.0;    // m from the organ's bounding box (at least its diagonal)
};

class ForceLimiter {
 public:
  static constexpr std::size_t kListedClamps = 1000;
  enum Reason : unsigned { non_finite = 1, magnitude = 2, step = 4 };
  struct Clamp {
    long frame;
    unsigned reasons;
    Eigen::Vector3d asked, sent;
  };

  explicit ForceLimiter(const DeviceSafetyConfig& config);
  // The force to send for frame `frame` (1-based) when the model gives `asked`.
  Eigen::Vector3d limit(long frame, const Eigen::Vector3d& asked);
  long clamped_frames() const { return clamped_; }
  long non_finite_frames() const { return non_finite_; }
  const std::vector<Clamp>& listed() const { return listed_; }
  // The artifact's "device_safety" member.
  nlohmann::json payload() const;

 private:
  DeviceSafetyConfig config_;
  Eigen::Vector3d previous_ = Eigen::Vector3d::Zero();
  long clamped_ = 0, non_finite_ = 0, magnitude_ = 0, step_ = 0;
  std::vector<Clamp> listed_;  // capacity reserved once
};

// The region a tip position must lie in: within `max_distance` of the organ's bounding box.
class Workspace {
 public:
  Workspace(const mesh::TetMesh& mesh, double max_distance);
  // Distance (m) from the box; 0 inside.
  double distance(const Eigen::Vector3d& p) const;
  bool contains(const Eigen::Vector3d& p) const { return distance(p) <= reach_; }
  double reach() const { return reach_; }

 private:
  Eigen::Vector3d lo_, hi_;
  double reach_;
};

}  // namespace softsim::haptic
