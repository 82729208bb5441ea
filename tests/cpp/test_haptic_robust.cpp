// A live scene with the inversion-robust law (stable neo-Hookean, Smith et al. 2018): the probe
// pressed far past the depth where the neo-Hookean TLED element inverts, the frames go on with no
// event, elements are inverted on the way and the force on the device stays finite; the same
// press with the neo-Hookean law is reported as events (the guard) and keeps answering too.
#include <gtest/gtest.h>

#include <cmath>

#include "softsim/haptic/haptic_run.hpp"
#include "softsim/haptic/haptic_scene.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/mesh/tet_mesh.hpp"

#include "support/scenes.hpp"

using namespace softsim;

namespace {

// The block of test_haptic.cpp: 8 x 8 x 4 cells, 10 x 10 x 5 cm, bottom fixed, E = 5 kPa, damped.
std::shared_ptr<const mesh::TetMesh> block() {
  return std::make_shared<const mesh::TetMesh>(test_scenes::cuboid(8, 8, 4, 0.1, 0.1, 0.05));
}

hybrid::DhdConfig config(const mesh::TetMesh& mesh, const std::string& model) {
  const nlohmann::json j = {{"mesh", "unused"},
                            {"material", {{"model", model}, {"E", 5000.0}, {"nu", 0.35}, {"density", 1000.0}}},
                            {"damping", {{"alpha", 10.0}}},
                            {"boundary", {{"fixed", {{{"set", "bottom"}}}}}},
                            {"solver", {{"kind", "explicit"}}}};
  return hybrid::read_dhd_config(io::JsonReader(j, "block.json"), mesh);
}

// 4× the block's height, straight down from the top centre over 0.2 s, then held.
haptic::ProbePath deep_press() {
  haptic::ProbePath path;
  path.origin = Eigen::Vector3d(0.05, 0.05, 0.05);
  path.signal.kind = multirate::ProbeSignal::Kind::kRampHold;
  path.signal.amplitude = 0.2;
  path.signal.ramp_time = 0.2;
  return path;
}

// The experiments' 100 N/m: stiff enough to drag the surface through the block, soft enough for
// the spring's once-per-frame coupling to stay stable (k Δt_frame² / m well below 4 for a surface
// node of this block).
haptic::HapticOptions spring() {
  haptic::HapticOptions opt;
  opt.probe_stiffness = 100;
  return opt;
}

int inverted_elements(const mesh::TetMesh& m, const double* u) {
  int n = 0;
  for (const auto& t : m.tets) {
    std::array<Eigen::Vector3d, 4> x;
    for (int a = 0; a < 4; ++a) x[a] = m.nodes[t[a]] + Eigen::Vector3d(u[3 * t[a]], u[3 * t[a] + 1], u[3 * t[a] + 2]);
    if (mesh::signed_volume(x[0], x[1], x[2], x[3]) <= 0) ++n;
  }
  return n;
}

}  // namespace

TEST(HapticRobust, TheStableNeoHookeanSceneRunsPastInversionWithoutEvents) {
  const auto mesh = block();
  haptic::HapticScene scene(mesh, config(*mesh, "stable_neo_hookean"), spring());
  const haptic::ProbePath path = deep_press();
  int most_inverted = 0;
  double largest = 0;
  for (long k = 1; k <= 400; ++k) {
    const Eigen::Vector3d f = scene.frame(path.at(k * 1e-3));
    ASSERT_TRUE(f.allFinite()) << "frame " << k;
    largest = std::max(largest, f.norm());
    most_inverted = std::max(most_inverted, inverted_elements(*mesh, scene.model().displacement()));
  }
  for (const auto& e : scene.events()) ADD_FAILURE() << "frame " << e.frame << ": " << e.message;
  EXPECT_GT(most_inverted, 0);  // the press did go past inversion
  EXPECT_TRUE(scene.in_contact());
  // The device feels the tissue resist: a force against the press, growing with depth.
  EXPECT_GT(largest, 1.0);
}

TEST(HapticRobust, TheSamePressWithTheNeoHookeanLawIsReportedAndTheFramesGoOn) {
  const auto mesh = block();
  haptic::HapticScene scene(mesh, config(*mesh, "neo_hookean_paper"), spring());
  const haptic::HapticRecord r = haptic::run_haptic(scene, deep_press(), 400);
  EXPECT_EQ(r.frames, 400);
  ASSERT_FALSE(scene.events().empty());
  EXPECT_NE(scene.events().front().message.find("inverted"), std::string::npos) << scene.events().front().message;
  for (const auto& f : r.force) EXPECT_TRUE(f.allFinite());
}
