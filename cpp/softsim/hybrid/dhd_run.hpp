#pragma once
// One dhd_sim run from a config: partition, time step, explicit or static solve, and the
// "dhd_result" payload; and the --bench measurement of four partitions.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/dynamics/stable_step.hpp"
#include "softsim/dynamics/static_solver.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/hybrid/dhd_scene.hpp"
#include "softsim/hybrid/small_strain_check.hpp"

namespace softsim::hybrid {

inline constexpr const char* kResultSchema = "dhd_result";
inline constexpr int kResultSchemaVersion = 1;
inline constexpr const char* kBenchSchema = "dhd_bench";
inline constexpr int kBenchSchemaVersion = 1;

struct DhdRun {
  std::vector<fem::ElementKind> kinds;
  dynamics::CriticalStep critical;
  std::optional<dynamics::SpectralStep> spectral;  // solver.critical_step "power_iteration"
  dynamics::StepChoice step;
  std::optional<dynamics::ExplicitResult> explicit_result;
  std::optional<dynamics::StaticResult> static_result;
  double setup_seconds = 0;  // critical step, element set and solver set-up (the partition excluded)
  double solve_seconds = 0;  // static runs: wall time of solve_static (0 for explicit runs)
  std::vector<DhdScene::CutEvent> cuts;  // the cut events of the run (config "cuts")
  std::vector<int> removed_elements;     // every element the cuts removed, ascending
  // The mesh separating cuts left (their node copies appended, elements re-pointed); null when
  // no cut separates. Displacements of the run have one entry per node of this mesh.
  std::shared_ptr<const mesh::TetMesh> cut_mesh;
  // The largest deformation of a small-strain element (000 §2.2.2's 10 % condition), over the
  // states between chunks of explicit steps and the final one (static: the solution).
  SmallStrainRecord small_strain;
};

// Throws InputError (bad step request, ...) or NumericalError (failure during the solve).
DhdRun run_dhd(const mesh::TetMesh& mesh, const DhdConfig& config, const dynamics::SnapshotFn& snapshot = {});
// The same with the partition already made: `kinds` as make_partition(mesh, config.partition).
// `progress` is called between chunks of explicit steps (see dynamics::ProgressFn).
// `on_scene` is called once the scene is set up (output that must follow its cuts keeps it).
DhdRun run_dhd(const mesh::TetMesh& mesh, const DhdConfig& config, std::vector<fem::ElementKind> kinds,
               const dynamics::SnapshotFn& snapshot, const dynamics::ProgressFn& progress = {},
               const std::function<void(const DhdScene&)>& on_scene = {});

// The artifact's "element_kind_legend": fem::kElementKinds in code order, one object per kind
// {"name", "small_strain", "description"} (element_kind value k is entry k).
nlohmann::json element_kind_legend();

nlohmann::json result_payload(const mesh::TetMesh& mesh, const DhdConfig& config, const DhdRun& run);

struct BenchRun {
  std::string partition;  // "all_tled", "all_linear", "all_corotational", "linear_fraction"
  double linear_fraction = 0;
  int threads = 1;
  int steps = 0;
  double steps_per_second = 0;
  std::array<double, fem::kNumElementKinds> ns_per_element{};  // 0 where the kind is absent
  double node_ns_per_node = 0;
};

// The configured scene (or the default bench scene without a boundary block) run with each
// partition and thread count; element kernels timed separately.
std::vector<BenchRun> run_bench(const mesh::TetMesh& mesh, const DhdConfig& config);
nlohmann::json bench_payload(const mesh::TetMesh& mesh, const DhdConfig& config, const std::vector<BenchRun>& runs);

// The bench's default scene: the "bottom" set fixed (if the mesh has it) and the node nearest
// the centre of the top face pushed down by 10 % of the height over `ramp_time`.
dynamics::Scene default_bench_scene(const mesh::TetMesh& mesh, double ramp_time);

}  // namespace softsim::hybrid
