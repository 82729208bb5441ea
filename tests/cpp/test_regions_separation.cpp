// Linked regions with cuts that separate along faces (019 in the regions of 001 §5): node copies
// change the mesh every region is built on, so the active region is built again on the cut mesh
// and resumes from the state it published, each copy from its node's. At the full rate that is
// the whole model's separation to round-off; in a smaller region the frames go on.
#include <gtest/gtest.h>

#include "softsim/haptic/haptic_scene.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/regions/region_tracker.hpp"
#include "support/haptic_block.hpp"

using namespace softsim;

namespace {

using Block = test_scenes::HapticBlock;
using test_scenes::press_down;

haptic::HapticOptions options(double radius = 0) {
  haptic::HapticOptions opt;
  opt.probe_stiffness = 100;
  if (radius > 0) {
    opt.use_regions = true;
    opt.regions.radius = radius;
  }
  return opt;
}

hybrid::DhdConfig separating(const Block& b, double damping) {
  hybrid::DhdConfig c = b.config(damping);
  c.separates = true;
  return c;
}

// A vertical blade drawn along x at y = y0 between heights z0 and z1.
cutting::BladeSweep along_x(double x0, double x1, double y0, double z0, double z1) {
  cutting::BladeSweep s;
  s.a0 = {x0, y0, z0};
  s.b0 = {x0, y0, z1};
  s.a1 = {x1, y0, z0};
  s.b1 = {x1, y0, z1};
  return s;
}

}  // namespace

TEST(RegionsWithSeparation, AtTheFullRateASeparatingCutIsTheWholeModels) {
  Block b;
  const haptic::ProbePath path = press_down({0.05, 0.04, 0.05}, 0.005, 0.2);
  haptic::HapticScene whole(b.mesh, separating(b, 15), options());
  haptic::HapticScene all(b.mesh, separating(b, 15), options(1.0));
  const auto sweep = along_x(0.03, 0.07, 0.056, 0.02, 0.07);
  std::vector<Eigen::Vector3d> fw, fa;
  for (long k = 0; k < 300; ++k) {
    if (k == 150) {
      const auto cw = whole.cut(sweep, hybrid::CutMode::separate);
      const auto ca = all.cut(sweep, hybrid::CutMode::separate);
      ASSERT_FALSE(cw.copies.empty());
      ASSERT_EQ(cw.copies, ca.copies);
      EXPECT_TRUE(cw.report.elements.empty());
    }
    fw.push_back(whole.frame(path.at(k * 1e-3)));
    fa.push_back(all.frame(path.at(k * 1e-3)));
  }
  ASSERT_TRUE(whole.events().empty());
  ASSERT_TRUE(all.events().empty());
  EXPECT_EQ(all.regions()->topology_stats().rebuilds, 1);
  double d = 0;
  for (std::size_t k = 0; k < fw.size(); ++k) d = std::max(d, (fw[k] - fa[k]).norm());
  EXPECT_LE(d, 1e-10 * fw.back().norm());
  const int n = whole.model().num_nodes();
  EXPECT_GT(n, b.mesh->num_nodes());
  for (int i = 0; i < 3 * n; ++i) EXPECT_NEAR(all.displacement()[i], whole.displacement()[i], 1e-12) << i / 3;
}

// A separating blade on the tool in a smaller region: each cut that splits nodes rebuilds the
// active region on the cut mesh; the frames go on without events and the published state covers
// every node of the cut mesh.
TEST(RegionsWithSeparation, ASeparatingBladeInASmallerRegionRebuildsItAndGoesOn) {
  Block b;
  haptic::HapticOptions opt = options(0.03);
  opt.contact = haptic::ContactMode::push;
  opt.blade = true;
  opt.blade_edge = Eigen::Vector3d(0, 0, 0.04);
  opt.blade_mode = hybrid::CutMode::separate;
  haptic::HapticScene scene(b.mesh, separating(b, 40), opt);
  for (long k = 0; k <= 400; ++k) scene.frame(Eigen::Vector3d(0.03 + 0.04 * k / 400.0, 0.052, 0.04));
  ASSERT_TRUE(scene.events().empty());
  const int n = scene.model().num_nodes();
  ASSERT_GT(n, b.mesh->num_nodes());
  EXPECT_GE(scene.regions()->topology_stats().rebuilds, 1);
  for (int i = 0; i < 3 * n; ++i) ASSERT_TRUE(std::isfinite(scene.displacement()[i]));
}
