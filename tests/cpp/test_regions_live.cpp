// The live scene with regions while it changes: the far field is recovered only when something
// reads it (a picture, a snapshot, a contact search that reaches it), with the device's forces
// bit for bit those of a scene that recovers it at every due frame; a served session without
// pictures recovers nothing; the cuts' times are the frames' own.
#include <unistd.h>

#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <string>

#include "softsim/haptic/haptic_run.hpp"
#include "softsim/haptic/haptic_scene.hpp"
#include "softsim/haptic/realtime_loop.hpp"

#include "support/haptic_block.hpp"
#include "support/scenes.hpp"

using namespace softsim;

namespace {

// The lines served through real pipes, as a bridge's would be: written whole, then the input
// closed (the lines and the answers both fit a pipe's buffer); the served record.
haptic::HapticRecord serve_through_pipes(haptic::HapticScene& scene, const std::string& text) {
  int in_pipe[2], out_pipe[2];
  if (::pipe(in_pipe) != 0 || ::pipe(out_pipe) != 0) throw std::runtime_error("pipe");
  if (::write(in_pipe[1], text.data(), text.size()) != static_cast<ssize_t>(text.size()))
    throw std::runtime_error("the lines did not fit the pipe");
  ::close(in_pipe[1]);
  haptic::ServedSession session = haptic::serve_lines(scene, in_pipe[0], out_pipe[1], haptic::ServeOptions{});
  ::close(in_pipe[0]);
  ::close(out_pipe[0]);
  ::close(out_pipe[1]);
  return std::move(session.record);
}

using Block = test_scenes::HapticBlock;

const Eigen::Vector3d kTop(0.05, 0.05, 0.05);

// A modal far field (Craig–Bampton, 4 modes) recovered for pictures every 10 frames.
haptic::HapticOptions modal_regions() {
  haptic::HapticOptions opt = test_scenes::spring_probe(100, 0.025);
  opt.regions.far_field_mass = true;
  opt.regions.far_field_modes = 4;
  opt.regions.secondary_every = 10;
  return opt;
}

// Pressed 4 mm over 0.05 s, then slid 3 cm along x at 0.3 m/s: the contact leaves the first
// region (hand-overs) and the far field moves.
Eigen::Vector3d press_and_slide(long k) {
  const double t = k * 1e-3;
  const double depth = 0.004 * std::min(1.0, t / 0.05);
  const double x = t > 0.05 ? std::min(0.03, 0.3 * (t - 0.05)) : 0.0;
  return kTop + Eigen::Vector3d(x - 0.015, 0, -depth);
}

}  // namespace

// A scene that reads its far field after every frame (a picture each frame) and one that never
// does send the same forces, bit for bit; the one nobody reads solves no recovery although
// recoveries fell due; the other solves at most one per due update.
TEST(LiveRegions, AFarFieldNobodyReadsIsNeverRecoveredAndTheForcesAreUnchanged) {
  Block b;
  haptic::HapticScene read(b.mesh, b.config(40), modal_regions());
  haptic::HapticScene unread(b.mesh, b.config(40), modal_regions());
  double checksum = 0;
  for (long k = 0; k < 200; ++k) {
    const Eigen::Vector3d fa = read.frame(press_and_slide(k));
    const Eigen::Vector3d fb = unread.frame(press_and_slide(k));
    ASSERT_EQ(fa, fb) << "frame " << k;
    const double* u = read.displacement();
    for (int i = 0; i < 3 * b.mesh->num_nodes(); ++i) checksum += u[i];
  }
  EXPECT_TRUE(std::isfinite(checksum));
  const auto ra = read.regions()->totals();
  const auto rb = unread.regions()->totals();
  EXPECT_GT(read.regions()->builds().switches, 0);  // the slide handed the contact over
  EXPECT_GT(rb.secondary_updates, 10);              // recoveries fell due ...
  // ... the unread scene solved only those its hand-overs needed (a successor starts from the
  // whole published field) and its contact walks that reached the far field near a hand-over;
  // the read one every due one.
  EXPECT_GE(rb.far_field_recoveries, unread.regions()->builds().switches);
  EXPECT_LT(4 * rb.far_field_recoveries, rb.secondary_updates);
  EXPECT_GE(ra.far_field_recoveries, ra.secondary_updates);
}

// Pictures read now and then show the far field exactly as a scene reading it every frame
// shows it at the same frames (the deferred solve writes what the due one would have).
TEST(LiveRegions, APictureReadLateShowsTheFarFieldOfItsDueFrame) {
  Block b;
  haptic::HapticScene every(b.mesh, b.config(40), modal_regions());
  haptic::HapticScene sometimes(b.mesh, b.config(40), modal_regions());
  const int n3 = 3 * b.mesh->num_nodes();
  int compared = 0;
  for (long k = 0; k < 150; ++k) {
    every.frame(press_and_slide(k));
    sometimes.frame(press_and_slide(k));
    const double* ue = every.displacement();
    if (k % 33 != 32) continue;
    const double* us = sometimes.displacement();
    for (int i = 0; i < n3; ++i) ASSERT_EQ(ue[i], us[i]) << "frame " << k << " dof " << i;
    ++compared;
  }
  EXPECT_EQ(compared, 4);
  EXPECT_LT(sometimes.regions()->totals().far_field_recoveries, every.regions()->totals().far_field_recoveries);
}

// The served loop without a visual stream (lines in, answers out, as a device bridge drives it)
// solves no far-field recovery at all for a grasp held in one region, and answers the offline
// run's forces for the same positions, bit for bit.
TEST(LiveRegions, ServedWithoutPicturesNoFarFieldRecoveryRunsAndTheAnswersAreTheOfflineOnes) {
  Block b;
  haptic::HapticOptions opt = modal_regions();
  auto press = [](long k) -> Eigen::Vector3d { return kTop + Eigen::Vector3d(0, 0, -0.004 * std::min(1.0, k / 50.0)); };
  haptic::HapticScene served(b.mesh, b.config(40), opt);
  std::ostringstream lines;
  lines.precision(17);
  const long frames = 120;
  for (long k = 0; k < frames; ++k) {
    const Eigen::Vector3d p = press(k);
    lines << (k + 1) * 1e-3 << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  }
  served.prepare(press(0));
  const haptic::HapticRecord record = serve_through_pipes(served, lines.str());
  ASSERT_EQ(record.frames, frames);
  EXPECT_GE(served.regions()->totals().secondary_updates, frames / 10 - 1);
  EXPECT_EQ(served.regions()->totals().far_field_recoveries, 0);
  haptic::HapticScene offline(b.mesh, b.config(40), opt);
  offline.prepare(press(0));
  for (long k = 0; k < frames; ++k) ASSERT_EQ(offline.frame(press(k)), record.force[k]) << "frame " << k;
}

// With regions the model itself does not step: a cut is recorded at the time of the frame that
// made it (a config's scheduled cut at its frame's start, one between frames at the last frame's
// end), as the whole model records its own.
TEST(LiveRegions, CutsAreRecordedAtTheirFramesTime) {
  Block b;
  hybrid::DhdConfig config = b.config(40);
  hybrid::CutSpec scheduled;
  scheduled.time = 0.0205;  // inside frame 21, [0.020, 0.021]
  scheduled.sweep = test_scenes::sweep_along_x(0.0, 0.1, 0.052, 0.01, 0.06);
  config.cuts.push_back(scheduled);
  haptic::HapticScene scene(b.mesh, config, test_scenes::spring_probe(100, 0.025));
  for (long k = 0; k < 30; ++k) scene.frame(kTop + Eigen::Vector3d(0.0, -0.02, -0.002));
  scene.cut(test_scenes::sweep_along_x(0.0, 0.1, 0.03, 0.01, 0.06));
  ASSERT_EQ(scene.model().cut_events().size(), 2u);
  EXPECT_NEAR(scene.cut_time(0), 0.020, 1e-12);
  EXPECT_NEAR(scene.cut_time(1), 0.030, 1e-12);
  haptic::HapticScene whole(b.mesh, config, test_scenes::spring_probe(100));
  for (long k = 0; k < 30; ++k) whole.frame(kTop + Eigen::Vector3d(0.0, -0.02, -0.002));
  ASSERT_EQ(whole.model().cut_events().size(), 1u);
  // The whole model cuts at its first explicit step at or past the time, inside frame 21.
  EXPECT_GE(whole.cut_time(0), 0.0205 - whole.dt());
  EXPECT_LE(whole.cut_time(0), 0.021);
}

namespace {

haptic::HapticOptions background(int swap_after_frames, double prefetch_fraction = 0.5) {
  haptic::HapticOptions opt = modal_regions();
  opt.regions.build_in_background = true;
  opt.regions.swap_after_frames = swap_after_frames;
  opt.regions.prefetch_fraction = prefetch_fraction;
  return opt;
}

std::vector<Eigen::Vector3d> forces(haptic::HapticScene& scene, long frames) {
  std::vector<Eigen::Vector3d> f;
  for (long k = 0; k < frames; ++k) f.push_back(scene.frame(press_and_slide(k)));
  return f;
}

double peak(const std::vector<Eigen::Vector3d>& f) {
  double p = 0;
  for (const auto& x : f) p = std::max(p, x.norm());
  return p;
}

}  // namespace

// A region built on the worker and swapped in at the frame that asked for it (and no region
// asked for ahead of the contact) is the inline build: the same hand-overs at the same frames
// and the same forces, bit for bit; the state carried over makes the successor continue.
TEST(LiveRegions, ABackgroundBuildSwappedInAtItsFrameIsTheInlineBuild) {
  Block b;
  haptic::HapticScene inline_scene(b.mesh, b.config(40), modal_regions());
  haptic::HapticScene worker_scene(b.mesh, b.config(40), background(0, 1e9));
  const auto fi = forces(inline_scene, 200);
  const auto fw = forces(worker_scene, 200);
  for (std::size_t k = 0; k < fi.size(); ++k) ASSERT_EQ(fi[k], fw[k]) << "frame " << k;
  EXPECT_GT(worker_scene.regions()->builds().background_builds, 1);
  EXPECT_EQ(worker_scene.regions()->builds().swaps, worker_scene.regions()->builds().background_builds);
  EXPECT_EQ(worker_scene.regions()->builds().builds, inline_scene.regions()->builds().builds);
}

// Swapped in a fixed number of frames after the request, waiting for the worker if needed, a
// run is the same whatever the worker's timing: two runs answer the same forces bit for bit.
TEST(LiveRegions, SwapsAtAFixedFrameAfterTheRequestAreReproducible) {
  Block b;
  haptic::HapticScene first(b.mesh, b.config(40), background(4));
  haptic::HapticScene second(b.mesh, b.config(40), background(4));
  const auto f1 = forces(first, 200);
  const auto f2 = forces(second, 200);
  for (std::size_t k = 0; k < f1.size(); ++k) ASSERT_EQ(f1[k], f2[k]) << "frame " << k;
  EXPECT_GT(first.regions()->builds().swaps, 1);
}

// A region swapped in mid-slide continues the state it replaces (positions, velocities, the far
// field's modes): at every swap the force moves by no more than the slide moves it from frame to
// frame elsewhere, and by under 2 % of the peak force, where a successor started from rest would
// drop the whole pressed force. Asked for ahead of the contact, no frame holds the contact. Over
// the run the forces stay within 3 % (RMS of the peak) of the inline scene's, whose regions lie
// elsewhere (it moves a region only when the contact leaves it).
TEST(LiveRegions, ARegionSwappedInMidRunContinuesTheStateItReplaces) {
  Block b;
  haptic::HapticScene inline_scene(b.mesh, b.config(40), modal_regions());
  haptic::HapticScene worker_scene(b.mesh, b.config(40), background(4, 0.3));
  std::vector<Eigen::Vector3d> fw, fi;
  std::vector<long> swap_frames;
  long swaps = 0;
  for (long k = 0; k < 200; ++k) {
    fi.push_back(inline_scene.frame(press_and_slide(k)));
    fw.push_back(worker_scene.frame(press_and_slide(k)));
    if (worker_scene.regions()->builds().swaps > swaps) {
      swaps = worker_scene.regions()->builds().swaps;
      if (k > 0) swap_frames.push_back(k);
    }
  }
  ASSERT_GE(swap_frames.size(), 2u);
  const double p = peak(fi);
  double sum = 0;
  for (std::size_t k = 0; k < fi.size(); ++k) sum += (fw[k] - fi[k]).squaredNorm();
  EXPECT_LT(std::sqrt(sum / fi.size()) / p, 0.03);
  // The largest frame-to-frame change of the force away from the swaps (the slide's own).
  double step = 0;
  for (std::size_t k = 1; k < fw.size(); ++k)
    if (std::find(swap_frames.begin(), swap_frames.end(), long(k)) == swap_frames.end())
      step = std::max(step, (fw[k] - fw[k - 1]).norm());
  EXPECT_EQ(worker_scene.live_stats().frames_held, 0);  // asked for ahead: never waited on
  for (long s : swap_frames) {
    EXPECT_LT((fw[s] - fw[s - 1]).norm() / p, 0.02) << "swap at frame " << s;
    EXPECT_LE((fw[s] - fw[s - 1]).norm(), step) << "swap at frame " << s;
  }
}

// A cut that reaches the far field: the region on the cut mesh is built on the worker while the
// current one answers (its primary engine cut at once, its far field as before the cut), then
// swapped in; the frames go on without events, the rebuild is counted, and the forces stay
// within 5 % (RMS of the peak) of the inline scene that rebuilds inside the frame.
TEST(LiveRegions, ACutReachingTheFarFieldIsRebuiltBesideTheFrames) {
  Block b;
  hybrid::DhdConfig config = b.config(40);
  hybrid::CutSpec far_cut;
  far_cut.time = 0.08;
  far_cut.sweep = test_scenes::sweep_along_x(0.0, 0.1, 0.085, 0.01, 0.06);  // beyond the region
  config.cuts.push_back(far_cut);
  auto press = [](long k) -> Eigen::Vector3d { return kTop + Eigen::Vector3d(0, 0, -0.004 * std::min(1.0, k / 50.0)); };
  haptic::HapticScene inline_scene(b.mesh, config, modal_regions());
  haptic::HapticScene worker_scene(b.mesh, config, background(3));
  inline_scene.prepare(press(0));
  worker_scene.prepare(press(0));
  std::vector<Eigen::Vector3d> fi, fw;
  for (long k = 0; k < 160; ++k) {
    fi.push_back(inline_scene.frame(press(k)));
    fw.push_back(worker_scene.frame(press(k)));
  }
  EXPECT_TRUE(worker_scene.events().empty());
  EXPECT_EQ(inline_scene.regions()->topology_stats().rebuilds, 1);
  EXPECT_EQ(worker_scene.regions()->topology_stats().rebuilds, 1);
  EXPECT_GE(worker_scene.regions()->builds().background_builds, 2);  // the first region, the cut one
  double sum = 0;
  for (std::size_t k = 0; k < fi.size(); ++k) sum += (fw[k] - fi[k]).squaredNorm();
  EXPECT_LT(std::sqrt(sum / fi.size()) / peak(fi), 0.05);
  EXPECT_GT(std::sqrt(sum / fi.size()), 0.0);  // the far field lagged the cut by three frames
}

// A modal far field recovered rarely (secondary_every 100000, nobody reading pictures) and one
// recovered every 10 frames answer the same forces, bit for bit, through a cut that reaches the
// far field: the region rebuilt on the cut mesh starts from the far field brought up to date at
// the cut (its displacement and, one step earlier, its motion), not from the last picture's.
TEST(LiveRegions, ARarelyRecoveredModalFarFieldHasNoTransientAfterACut) {
  Block b;
  hybrid::DhdConfig config = b.config(40);
  hybrid::CutSpec far_cut;
  far_cut.time = 0.063;
  far_cut.sweep = test_scenes::sweep_along_x(0.0, 0.1, 0.085, 0.01, 0.06);
  config.cuts.push_back(far_cut);
  haptic::HapticOptions often = modal_regions();
  haptic::HapticOptions rarely = often;
  rarely.regions.secondary_every = 100000;
  haptic::HapticScene a(b.mesh, config, often);
  haptic::HapticScene c(b.mesh, config, rarely);
  const haptic::ProbePath path = test_scenes::press_down(kTop, 0.004, 0.05);
  const haptic::HapticRecord ra = haptic::run_haptic(a, path, 150);
  const haptic::HapticRecord rc = haptic::run_haptic(c, path, 150);
  ASSERT_EQ(a.regions()->topology_stats().rebuilds, 1);
  ASSERT_EQ(c.regions()->topology_stats().rebuilds, 1);
  EXPECT_EQ(c.regions()->totals().secondary_updates, 1);  // the one the cut asked for
  for (std::size_t k = 0; k < ra.force.size(); ++k) ASSERT_EQ(ra.force[k], rc.force[k]) << "frame " << k;
}

// With swaps at a fixed frame after the request, the served loop (lines in, answers out) answers
// a scripted slide that changes regions with the offline run's forces for the same positions, bit
// for bit, whatever the worker's timing in either (the mode that guarantees served = offline
// while regions change; the default -1 swaps when the worker is done and does not).
TEST(LiveRegions, ServedWithFixedSwapFramesEqualsTheOfflineRunAcrossRegionChanges) {
  Block b;
  const haptic::HapticOptions opt = background(3, 0.3);
  haptic::HapticScene served(b.mesh, b.config(40), opt);
  const long frames = 200;
  std::ostringstream lines;
  lines.precision(17);
  for (long k = 0; k < frames; ++k) {
    const Eigen::Vector3d p = press_and_slide(k);
    lines << (k + 1) * 1e-3 << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  }
  served.prepare(press_and_slide(0));
  const haptic::HapticRecord record = serve_through_pipes(served, lines.str());
  ASSERT_EQ(record.frames, frames);
  EXPECT_GT(served.regions()->builds().swaps, 2);
  haptic::HapticScene offline(b.mesh, b.config(40), opt);
  offline.prepare(press_and_slide(0));
  for (long k = 0; k < frames; ++k) ASSERT_EQ(offline.frame(press_and_slide(k)), record.force[k]) << "frame " << k;
}
