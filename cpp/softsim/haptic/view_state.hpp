#pragma once
// What a live scene's viewer sees, and how it gets it without ever holding up the haptic loop:
// the loop writes the latest state into one of three buffers and publishes it with one atomic
// exchange; the viewer takes the newest published one with another (a triple buffer). Neither
// side waits for the other or allocates once the buffers are sized: a slow or closed viewer
// only skips states.
#include <atomic>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace softsim::haptic {

// The surface the viewer draws: changes only when a cut changes the mesh.
struct ViewTopology {
  long version = -1;
  int nodes = 0;
  std::vector<float> reference;       // 3 per node: reference positions X (m)
  std::vector<std::int32_t> triangles;  // 3 per triangle: the live boundary triangles, outward
};

struct ViewState {
  long frame = 0;       // frames computed
  double time = 0;      // s, the loop's clock (frame × frame step)
  Eigen::Vector3d tip = Eigen::Vector3d::Zero(), force = Eigen::Vector3d::Zero();  // m, N (on the tool)
  bool contact = false, blade = false;
  // The physics loop's frame compute time over the frames since the previous state (s), the
  // frames over the frame period since the start (deadline misses), and how late frames started
  // against the wall clock (s, the largest since the previous state).
  double compute_mean = 0, compute_max = 0, start_lag_max = 0;
  long deadline_misses = 0, window_frames = 0;
  long events = 0, cuts = 0, samples = 0, samples_dropped = 0;
  std::vector<float> positions;  // 3 per node: x = X + u (m)
  // Per node, with linked regions: 0 far field, 1 primary interior, 2 interface; empty without.
  std::vector<std::uint8_t> region;
  ViewTopology topology;
};

// Single writer (the haptic loop), single reader (the viewer's thread).
class StateBuffer {
 public:
  ViewState& back() { return buffers_[back_]; }
  // The writer's back buffer becomes the newest state.
  void publish() { back_ = middle_.exchange(back_ | kFresh) & kIndex; }
  // The reader takes the newest state if one was published since; false otherwise.
  bool take() {
    if (!(middle_.load() & kFresh)) return false;
    front_ = middle_.exchange(front_) & kIndex;
    return true;
  }
  const ViewState& front() const { return buffers_[front_]; }
  ViewState& buffer(int i) { return buffers_[i]; }  // sizing before the loop starts

 private:
  static constexpr int kIndex = 3, kFresh = 4;
  ViewState buffers_[3];
  int back_ = 0, front_ = 2;
  std::atomic<int> middle_{1};
};

// Samples from the transport's thread to the loop's: a fixed ring, single producer, single
// consumer. A full ring drops the sample (counted), it never waits.
template <class T, std::size_t N>
class SampleQueue {
 public:
  bool push(const T& v) {
    const std::size_t h = head_.load(std::memory_order_relaxed);
    if (h - tail_.load(std::memory_order_acquire) == N) return false;
    items_[h % N] = v;
    head_.store(h + 1, std::memory_order_release);
    return true;
  }
  bool pop(T& v) {
    const std::size_t t = tail_.load(std::memory_order_relaxed);
    if (t == head_.load(std::memory_order_acquire)) return false;
    v = items_[t % N];
    tail_.store(t + 1, std::memory_order_release);
    return true;
  }

 private:
  T items_[N]{};
  std::atomic<std::size_t> head_{0}, tail_{0};
};

}  // namespace softsim::haptic
