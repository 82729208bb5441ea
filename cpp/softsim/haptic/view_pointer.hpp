#pragma once
// The pointer as a haptic device: samples of the tool tip arrive at the pointer's rate (60-120 Hz
// from a browser page, or a device bridge's rate), stamped with the sender's clock, and the 1 kHz
// loop reads the tip at each frame's time by linear interpolation between the two samples around
// it, as a recorded trajectory is read (probe_path.hpp, RecordedPath::at). The sender's clock is
// mapped onto the loop's once, at the first sample, with a play-out delay of `latency` so that the
// next sample has normally arrived when the loop needs it; a sample that arrives later holds the
// tip at the last one until it comes. A sender whose clock jumps (a tab put in the background and
// back) is mapped again, the tip moving from where it is to the new samples over the delay.
#include <array>
#include <cstddef>

#include <Eigen/Core>

namespace softsim::haptic {

struct PointerSample {
  double t = 0;                                      // s, the sender's clock (strictly increasing)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // tool tip (m, world)
  bool blade = false;                                // the tool is the blade (it cuts as it moves)
  Eigen::Vector3d edge = Eigen::Vector3d::Zero();    // the blade's edge, tip ± edge/2 (m)
};

class PointerTrack {
 public:
  // `start`: the tip before any sample; `latency`: the play-out delay (s); `resync`: a sample
  // whose place on the loop's clock is further than this from where it is expected re-maps the
  // sender's clock (s).
  PointerTrack(const Eigen::Vector3d& start, double latency, double resync = 0.25);

  // A sample received by the loop at its time `now` (s). Samples must come in increasing `t`
  // (the transport checks it; an older sample is ignored here).
  void push(const PointerSample& s, double now);
  // A new sender (the clock mapping starts again at its first sample).
  void restart() { anchored_ = false; }
  // The tip at the loop's time `now` (s): linear between the samples around it, held at the last
  // one past it. The blade state and edge are those of the sample the segment starts at.
  const PointerSample& at(double now);
  double latency() const { return latency_; }

 private:
  static constexpr std::size_t kCapacity = 64;  // samples kept (more than a play-out delay holds)
  const PointerSample& sample(std::size_t i) const { return ring_[(first_ + i) % kCapacity]; }
  void append(const PointerSample& s);

  std::array<PointerSample, kCapacity> ring_{};  // samples on the loop's clock, oldest first
  std::size_t first_ = 0, count_ = 0;
  double latency_, resync_;
  double offset_ = 0;     // loop time = sender time + offset
  double last_sent_ = 0;  // the last sample's time on the sender's clock
  bool anchored_ = false;
  PointerSample current_;  // the last answer of at()
};

}  // namespace softsim::haptic
