#pragma once
// A haptic scene driven frame by frame, offline from a generated or recorded input (run mode)
// or live from a device bridge (realtime_loop.hpp), with what each frame produced and cost,
// and the "haptic_result" payload haptic_sim writes.
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "softsim/haptic/device_safety.hpp"
#include "softsim/haptic/haptic_config.hpp"
#include "softsim/haptic/haptic_scene.hpp"

namespace softsim::haptic {

inline constexpr const char* kHapticSchema = "haptic_result";
inline constexpr int kHapticSchemaVersion = 1;

// The record of a run: one entry per frame, arrays sized before the loop.
struct HapticRecord {
  std::vector<double> time;               // s: frame k ends at (k + 1) × frame step (input time in real time)
  std::vector<Eigen::Vector3d> probe;     // tip position (m)
  std::vector<Eigen::Vector3d> force;     // on the tool (N), as sent to the device
  std::vector<char> contact;              // in contact after the frame
  std::vector<double> compute_seconds;    // wall time of the frame's computation
  long frames = 0;
  // Members added to the artifact's payload as they are ("device_safety", "session").
  nlohmann::json reports = nlohmann::json::object();
  void reserve(long n);
  void push(double t, const Eigen::Vector3d& p, const Eigen::Vector3d& f, bool in_contact, double seconds);
};

// Frame-time statistics against the frame period (the deadline).
struct FrameTimeSummary {
  long frames = 0;
  double p50 = 0, p99 = 0, max = 0;  // s
  long deadline_misses = 0;          // frames whose computation took longer than the frame period
};
FrameTimeSummary summarize_frame_times(const std::vector<double>& seconds, double frame_step);

// `frames` frames of the input path from the scene's current state. With `limiter`, each force
// is what the device would be sent (device_safety.hpp); with `workspace`, a tip position out of
// it is an InputError naming the frame.
HapticRecord run_haptic(HapticScene& scene, const ProbePath& path, long frames, ForceLimiter* limiter = nullptr,
                        const Workspace* workspace = nullptr);

nlohmann::json haptic_payload(const HapticConfig& config, const HapticScene& scene, const HapticRecord& record,
                              const std::string& mode);

}  // namespace softsim::haptic
