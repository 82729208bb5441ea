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
using test_scenes::spring_probe;

hybrid::DhdConfig separating(const Block& b, double damping) {
  hybrid::DhdConfig c = b.config(damping);
  c.separates = true;
  return c;
}

}  // namespace

TEST(RegionsWithSeparation, AtTheFullRateASeparatingCutIsTheWholeModels) {
  Block b;
  const haptic::ProbePath path = press_down({0.05, 0.04, 0.05}, 0.005, 0.2);
  haptic::HapticScene whole(b.mesh, separating(b, 15), spring_probe());
  haptic::HapticScene all(b.mesh, separating(b, 15), spring_probe(100, 1.0));
  const auto sweep = test_scenes::sweep_along_x(0.03, 0.07, 0.056, 0.02, 0.07);
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
  haptic::HapticScene scene(b.mesh, separating(b, 40), test_scenes::vertical_blade(hybrid::CutMode::separate, 0.03));
  test_scenes::draw_blade_across(scene);
  ASSERT_TRUE(scene.events().empty());
  const int n = scene.model().num_nodes();
  ASSERT_GT(n, b.mesh->num_nodes());
  EXPECT_GE(scene.regions()->topology_stats().rebuilds, 1);
  for (int i = 0; i < 3 * n; ++i) ASSERT_TRUE(std::isfinite(scene.displacement()[i]));
}
