#pragma once
// The live scene behind the viewer (haptic_sim view): the haptic frames at a fixed wall-clock
// rate on a thread of their own, the tool tip read from pointer samples interpolated to the frame
// rate (view_pointer.hpp), the blade cutting along the pointer's path, and the latest state handed
// to the viewer through a triple buffer (view_state.hpp). The loop never waits for the viewer or
// the transport. Every frame's tip, force and compute time is recorded: the tips as a trajectory
// `haptic_sim run` replays with input kind "recorded" (the same forces, bit for bit, for a
// session without cuts).
#include <atomic>
#include <exception>
#include <string>
#include <thread>

#include "softsim/haptic/device_safety.hpp"
#include "softsim/haptic/haptic_run.hpp"
#include "softsim/haptic/haptic_scene.hpp"
#include "softsim/haptic/view_pointer.hpp"
#include "softsim/haptic/view_state.hpp"

namespace softsim::haptic {

struct ViewLoopOptions {
  double latency = 0.025;  // s: the pointer's play-out delay (more than one sample interval at 60 Hz)
  int state_every = 16;    // frames per published state (16: about 60 Hz at 1 kHz)
  long max_frames = 0;     // stop after this many frames (0: until stopped)
  bool paced = true;       // false: frames back to back, not at the wall clock (tests)
  ForceLimiter* limiter = nullptr;  // what a device may be sent, as in run and serve (device_safety.hpp)
};

class ViewLoop {
 public:
  // `start`: the tip before the first sample (the config's input start, where `prepare` built
  // the regions).
  ViewLoop(HapticScene& scene, const Eigen::Vector3d& start, const ViewLoopOptions& options);
  ~ViewLoop();
  ViewLoop(const ViewLoop&) = delete;
  ViewLoop& operator=(const ViewLoop&) = delete;

  // Starts the frames on their own thread; `on_end` is called from it when they end by
  // themselves (max_frames reached, or an error: see rethrow()).
  void start(std::function<void()> on_end = {});
  // Ends the frames and joins the thread (idempotent).
  void stop();
  // Transport side (one producer thread): a sample of the tip; false when the queue is full.
  bool push(const PointerSample& s);
  // Transport side: a new sender; its clock is mapped afresh at its first sample.
  void new_sender() { restart_.store(true); }
  // Viewer side (one consumer thread): the newest state, if one was published since.
  bool take_state() { return states_.take(); }
  const ViewState& state() const { return states_.front(); }
  // After stop(): the record of every frame, and the error that ended the loop, if any.
  const HapticRecord& record() const { return record_; }
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }
  // The frames' tips as lines "t x y z" (t = k × frame step, the time `run` reads frame k at),
  // every value round-tripping exactly. InputError naming the path when it cannot be written.
  void write_trajectory(const std::string& path) const;

 private:
  void run();
  void frame(long k);
  void blade_cut(const PointerSample& s);
  void publish(long k);
  void fill_topology(ViewTopology& t);

  HapticScene& scene_;
  ViewLoopOptions options_;
  PointerTrack track_;
  SampleQueue<PointerSample, 1024> samples_;
  StateBuffer states_;
  HapticRecord record_;
  std::thread thread_;
  std::atomic<bool> stop_{false}, restart_{false};
  std::atomic<long> dropped_{0};
  std::function<void()> on_end_;
  std::exception_ptr error_;
  // Loop-thread state.
  long samples_seen_ = 0;
  Eigen::Vector3d previous_tip_ = Eigen::Vector3d::Zero();
  bool blade_ = false;
  long topology_version_ = 0;
  std::size_t cuts_seen_ = 0;
  int nodes_seen_ = 0;
  double window_sum_ = 0, window_max_ = 0, lag_max_ = 0;
  long window_frames_ = 0, deadline_misses_ = 0;
};

}  // namespace softsim::haptic
