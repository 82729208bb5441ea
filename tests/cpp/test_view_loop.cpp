// The live scene behind haptic_sim view (haptic/view_loop.hpp): a blade carried by the pointer
// cuts with the scene's own machinery, exactly as a blade configured on the tool cuts along the
// same tips; the frames run whether or not anyone reads their states.
#include <gtest/gtest.h>

#include <future>

#include "softsim/haptic/view_loop.hpp"
#include "support/haptic_block.hpp"

using namespace softsim;
using softsim::test_scenes::HapticBlock;

namespace {

// Runs `frames` unpaced frames of a loop fed `samples` before it starts; returns when they end.
void run_loop(haptic::ViewLoop& loop, const std::vector<haptic::PointerSample>& samples) {
  for (const auto& s : samples) ASSERT_TRUE(loop.push(s));
  std::promise<void> ended;
  loop.start([&] { ended.set_value(); });
  ended.get_future().wait();
  loop.stop();
  loop.rethrow();
}

}  // namespace

TEST(ViewLoop, APointersBladeCutsExactlyAsABladeOnTheToolAlongTheSameTips) {
  const HapticBlock block;
  const Eigen::Vector3d edge(0, 0, 0.04);  // vertical, 4 cm
  haptic::HapticOptions probe = test_scenes::spring_probe(100);
  probe.contact = haptic::ContactMode::push;
  // The pointer: the tip 1 cm below the top, drawn along x from 3 to 7 cm at y = 5.2 cm in
  // 0.2 s, one sample every 10 ms, every one carrying the blade.
  std::vector<haptic::PointerSample> samples;
  for (int k = 0; k <= 20; ++k) {
    haptic::PointerSample s;
    s.t = 50 + 0.01 * k;
    s.position = Eigen::Vector3d(0.03 + 0.002 * k, 0.052, 0.04);
    s.blade = true;
    s.edge = edge;
    samples.push_back(s);
  }
  haptic::HapticScene live(block.mesh, block.config(20), probe);
  haptic::ViewLoopOptions options;
  options.paced = false;
  options.max_frames = 300;
  haptic::ViewLoop loop(live, samples.front().position, options);  // nothing is read from it
  run_loop(loop, samples);
  const haptic::HapticRecord& r = loop.record();
  ASSERT_EQ(r.frames, 300);
  // The tips were interpolated between the samples: more distinct tips than samples.
  std::set<double> xs;
  for (const auto& p : r.probe) xs.insert(p.x());
  EXPECT_GT(xs.size(), 150u);
  EXPECT_EQ(r.probe.back(), samples.back().position);

  // The same tips through a scene whose tool carries the same blade (HapticOptions::blade).
  haptic::HapticOptions with_blade = probe;
  with_blade.blade = true;
  with_blade.blade_edge = edge;
  haptic::HapticScene reference(block.mesh, block.config(20), with_blade);
  for (long k = 0; k < r.frames; ++k) {
    const Eigen::Vector3d f = reference.frame(r.probe[k]);
    ASSERT_EQ(f, r.force[k]) << "frame " << k;
  }
  ASSERT_GT(live.model().cut_events().size(), 0u);
  EXPECT_EQ(live.model().cut_events().size(), reference.model().cut_events().size());
  double pressed = 0;  // the tip pressed the surface before the blade opened it under the tip
  for (const auto& f : r.force) pressed = std::max(pressed, f.norm());
  EXPECT_GT(pressed, 0.01);
}

// The page's pointer drives the scene as a device does, so its forces go through the same
// device limits as run and serve: a press that asks more than max_force is sent max_force at
// most, and the limiter records the clamps.
TEST(ViewLoop, ThePointersForcesGoThroughTheDevicesForceLimit) {
  const HapticBlock block;
  haptic::HapticOptions probe = test_scenes::spring_probe(100);
  probe.contact = haptic::ContactMode::push;
  std::vector<haptic::PointerSample> samples;  // the tip pressed 1 cm into the top over 0.2 s
  for (int k = 0; k <= 20; ++k) {
    haptic::PointerSample s;
    s.t = 50 + 0.01 * k;
    s.position = Eigen::Vector3d(0.03, 0.03, 0.03 - 0.0005 * k);
    samples.push_back(s);
  }
  haptic::DeviceSafetyConfig safety;
  safety.max_force = 0.05;  // N: below what the press asks
  haptic::ForceLimiter limiter(safety);
  haptic::HapticScene live(block.mesh, block.config(20), probe);
  haptic::ViewLoopOptions options;
  options.paced = false;
  options.max_frames = 300;
  options.limiter = &limiter;
  haptic::ViewLoop loop(live, samples.front().position, options);
  run_loop(loop, samples);
  const haptic::HapticRecord& r = loop.record();
  double largest = 0;
  for (const auto& f : r.force) largest = std::max(largest, f.norm());
  EXPECT_LE(largest, safety.max_force * (1 + 1e-12));
  EXPECT_GT(largest, 0.5 * safety.max_force);
  EXPECT_GT(limiter.payload()["max_force_frames"].get<long>(), 0);
}
