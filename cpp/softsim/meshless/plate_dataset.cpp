#include "softsim/meshless/plate_dataset.hpp"

namespace softsim::meshless {

MeshlessProblem plate_problem(const PlateScene& scene) {
  MeshlessProblem p;
  p.nodes = plate_nodes(scene);
  p.origin = Eigen::Vector3d::Zero();
  p.size = scene.size;
  p.cells = scene.background_cells;
  p.gauss_order = scene.gauss_order;
  p.youngs_modulus = scene.youngs_modulus;
  p.poisson_ratio = scene.poisson_ratio;
  p.constraints = plate_constraints(scene);
  p.mean_spacing = plate_mean_spacing(scene);
  return p;
}

SceneLayout plate_layout(const PlateScene& scene) {
  SceneLayout l;
  l.reported_nodes = plate_top_nodes(scene);
  l.fixed_nodes = plate_fixed_nodes(scene);
  l.loaded_node_index = plate_loaded_node_index(scene);
  l.loaded_node_number = plate_loaded_node_number(scene);
  l.body_force = scene.body_force;
  return l;
}

std::vector<PlateRun> run_plate_sets(const PlateScene& scene, const RpimSettings& settings,
                                     const std::vector<std::vector<Eigen::Vector3d>>& force_sets,
                                     bool stiffness_conditioning) {
  return run_scene_sets(plate_problem(scene), plate_layout(scene), settings, force_sets, stiffness_conditioning);
}

PlateRun run_plate(const PlateScene& scene, const RpimSettings& settings, const std::vector<Eigen::Vector3d>& forces,
                   bool stiffness_conditioning) {
  return std::move(run_plate_sets(scene, settings, {forces}, stiffness_conditioning).front());
}

}  // namespace softsim::meshless
