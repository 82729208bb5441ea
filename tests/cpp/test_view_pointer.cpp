// The pointer as a haptic device (haptic/view_pointer.hpp) and the hand-over of states to a viewer
// (haptic/view_state.hpp): samples at a pointer's rate read at the 1 kHz frames by linear
// interpolation, one play-out delay late; a sender whose clock jumps is mapped afresh without a
// jump of the tip; a reader of the triple buffer always sees a whole state, the newest.
#include <gtest/gtest.h>

#include <thread>

#include "softsim/haptic/view_pointer.hpp"
#include "softsim/haptic/view_state.hpp"

using namespace softsim::haptic;

namespace {

PointerSample sample(double t, double x) {
  PointerSample s;
  s.t = t;
  s.position = Eigen::Vector3d(x, 2 * x, -x);
  return s;
}

}  // namespace

TEST(PointerTrack, SamplesAtAPointersRateAreInterpolatedToTheFramesOneDelayLate) {
  const double latency = 0.025, h = 1e-3, rate = 60;
  const Eigen::Vector3d start(0, 0, 0);
  PointerTrack track(start, latency);
  // The sender's clock starts at 100 s; x(t) = 0.01 (t - 100) m, one sample every 1/60 s, each
  // received at the first frame after it was sent.
  int next = 0;
  double max_error = 0;
  for (long k = 0; k < 1000; ++k) {
    const double now = k * h;
    while (next / rate <= now) {
      track.push(sample(100 + next / rate, 0.01 * next / rate), now);
      ++next;
    }
    const Eigen::Vector3d p = track.at(now).position;
    if (now >= 2 * latency) {
      // Past the first delay the tip is x at the sender's time now − latency: the samples lie on a
      // line, so their linear interpolation is the line.
      const double expected = 0.01 * (now - latency);
      max_error = std::max(max_error, (p - Eigen::Vector3d(expected, 2 * expected, -expected)).norm());
    }
  }
  EXPECT_LT(max_error, 1e-12);
}

TEST(PointerTrack, BeforeTheFirstSampleTheTipHoldsAndThenMovesThereOverTheDelay) {
  PointerTrack track(Eigen::Vector3d(1, 1, 1), 0.02);
  EXPECT_EQ(track.at(0.0).position, Eigen::Vector3d(1, 1, 1));
  track.push(sample(5.0, 3.0), 0.1);  // arrives at 0.1 s: played at 0.12 s
  EXPECT_EQ(track.at(0.1).position, Eigen::Vector3d(1, 1, 1));
  const Eigen::Vector3d half = track.at(0.11).position;
  EXPECT_NEAR(half.x(), 2.0, 1e-12);
  EXPECT_NEAR(half.y(), 3.5, 1e-12);
  EXPECT_EQ(track.at(0.2).position, sample(0, 3.0).position);  // held at the last sample
}

TEST(PointerTrack, ASenderWhoseClockJumpsIsMappedAfreshWithoutAJumpOfTheTip) {
  PointerTrack track(Eigen::Vector3d::Zero(), 0.02);
  for (int k = 0; k < 10; ++k) track.push(sample(k * 0.01, 0.001 * k), k * 0.01);
  const Eigen::Vector3d before = track.at(0.1).position;
  // The tab was in the background for 30 s: its next sample is far ahead of the mapping.
  track.push(sample(30.0, 0.05), 0.1);
  EXPECT_EQ(track.at(0.1).position, before);  // the tip starts from where it is
  EXPECT_NEAR(track.at(0.11).position.x(), 0.5 * (before.x() + 0.05), 1e-12);
  EXPECT_NEAR(track.at(0.12).position.x(), 0.05, 1e-12);
  // An older sample than the last is ignored.
  track.push(sample(29.0, 1.0), 0.12);
  EXPECT_NEAR(track.at(0.2).position.x(), 0.05, 1e-12);
}

TEST(StateBuffer, TheReaderAlwaysGetsAWholeStateAndTheNewestOne) {
  StateBuffer buffer;
  for (int i = 0; i < 3; ++i) buffer.buffer(i).positions.assign(300, 0.0f);
  EXPECT_FALSE(buffer.take());
  std::atomic<bool> done{false};
  std::atomic<long> taken{0};
  long published = 0;
  // The writer publishes until the reader has taken many states (on a busy machine the reader
  // may start late), as the haptic loop does whatever the viewer does.
  std::thread writer([&] {
    for (long k = 1; taken.load() < 2000 && k < 100000000; ++k) {
      ViewState& s = buffer.back();
      s.frame = k;
      for (float& x : s.positions) x = static_cast<float>(k % 1000);  // every value written
      buffer.publish();
      published = k;
    }
    done.store(true);
  });
  long last = 0, torn = 0;
  while (!done.load()) {
    if (!buffer.take()) continue;
    const ViewState& s = buffer.front();
    taken.fetch_add(1);
    for (float x : s.positions) torn += x != static_cast<float>(s.frame % 1000);
    EXPECT_GT(s.frame, last);  // each state taken is newer than the one before
    last = s.frame;
  }
  writer.join();
  buffer.take();
  EXPECT_EQ(buffer.front().frame, published);  // the last one published is the one seen last
  EXPECT_EQ(torn, 0);
  EXPECT_GE(taken.load(), 2000);
}

TEST(SampleQueue, AFullQueueDropsInsteadOfWaiting) {
  SampleQueue<int, 4> q;
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(q.push(i));
  EXPECT_FALSE(q.push(9));
  int v = -1;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(q.pop(v));
    EXPECT_EQ(v, i);
  }
  EXPECT_FALSE(q.pop(v));
}
