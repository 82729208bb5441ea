#include "softsim/hybrid/dhd_vtu.hpp"

#include "softsim/hybrid/result_vtu.hpp"

namespace softsim::hybrid {

DhdRun run_dhd_writing_vtu(const mesh::TetMesh& mesh, const DhdConfig& config, const dynamics::ProgressFn& progress) {
  const std::vector<fem::ElementKind> kinds = make_partition(mesh, config.partition);
  VtuOutput vtu(mesh, kinds, config);
  DhdRun run = run_dhd(mesh, config, kinds, vtu.snapshot(), progress,
                       [&vtu](const DhdScene& scene) { vtu.follow_cuts(scene); });
  vtu.follow_cuts(nullptr);  // the scene is gone; the final file reads run.removed_elements
  vtu.write_final(run);
  return run;
}

}  // namespace softsim::hybrid
