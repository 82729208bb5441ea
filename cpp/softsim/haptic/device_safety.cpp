#include "softsim/haptic/device_safety.hpp"

#include <algorithm>
#include <cmath>

namespace softsim::haptic {

ForceLimiter::ForceLimiter(const DeviceSafetyConfig& config) : config_(config) { listed_.reserve(kListedClamps); }

Eigen::Vector3d ForceLimiter::limit(long frame, const Eigen::Vector3d& asked) {
  unsigned reasons = 0;
  Eigen::Vector3d sent = asked;
  if (!asked.allFinite()) {
    reasons |= non_finite;
    sent.setZero();
    ++non_finite_;
  } else {
    const double norm = sent.norm();
    if (norm > config_.max_force) {
      sent *= config_.max_force / norm;
      reasons |= magnitude;
      ++magnitude_;
    }
    // Both ends of the step lie inside the ball of radius max_force, so the limited force does too.
    const Eigen::Vector3d change = sent - previous_;
    const double change_norm = change.norm();
    if (!sent.isZero(0) && change_norm > config_.max_force_step) {
      sent = previous_ + change * (config_.max_force_step / change_norm);
      reasons |= step;
      ++step_;
    }
  }
  previous_ = sent;
  if (reasons) {
    ++clamped_;
    if (listed_.size() < kListedClamps) listed_.push_back({frame, reasons, asked, sent});
  }
  return sent;
}

namespace {

nlohmann::json vec(const Eigen::Vector3d& v) {
  // A non-finite value has no JSON number: it is written as null.
  nlohmann::json a = nlohmann::json::array();
  for (int c = 0; c < 3; ++c) a.push_back(std::isfinite(v[c]) ? nlohmann::json(v[c]) : nlohmann::json(nullptr));
  return a;
}

}  // namespace

nlohmann::json ForceLimiter::payload() const {
  nlohmann::json clamps = nlohmann::json::array();
  for (const Clamp& c : listed_) {
    nlohmann::json why = nlohmann::json::array();
    if (c.reasons & non_finite) why.push_back("non_finite");
    if (c.reasons & magnitude) why.push_back("max_force");
    if (c.reasons & step) why.push_back("max_force_step");
    clamps.push_back({{"frame", c.frame}, {"reasons", why}, {"asked", vec(c.asked)}, {"sent", vec(c.sent)}});
  }
  return {{"max_force", config_.max_force},
          {"max_force_step", config_.max_force_step},
          {"max_distance", config_.max_distance},
          {"clamped_frames", clamped_},
          {"non_finite_frames", non_finite_},
          {"max_force_frames", magnitude_},
          {"max_force_step_frames", step_},
          {"clamps", clamps}};
}

Workspace::Workspace(const mesh::TetMesh& mesh, double max_distance) {
  const auto box = mesh::bounding_box(mesh);
  lo_ = box.first;
  hi_ = box.second;
  reach_ = std::max(max_distance, (hi_ - lo_).norm());
}

double Workspace::distance(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d outside = (lo_ - p).cwiseMax(p - hi_).cwiseMax(0.0);
  return outside.norm();
}

}  // namespace softsim::haptic
