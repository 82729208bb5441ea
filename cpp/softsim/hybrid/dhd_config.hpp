#pragma once
// The dhd_sim configuration (documented in cpp/apps/dhd_sim.md), read strictly from JSON:
// every key is checked, node selectors are resolved against the mesh, and any problem is an
// InputError naming the file and JSON pointer. Defaults are the member initialisers of these
// structs (and of the library's: PartitionSpec, Scene's Ramp, StaticOptions, ...): the reader
// falls back to them, and tests/cpp/test_config_docs.cpp checks dhd_sim.md's tables against them.
#include <optional>
#include <string>
#include <vector>

#include "softsim/dynamics/scene.hpp"
#include "softsim/dynamics/static_solver.hpp"
#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/linear_rows.hpp"
#include "softsim/hybrid/partition.hpp"
#include "softsim/hybrid/cut_config.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/io/vtu_writer.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::hybrid {

// How Δt_cr is found: 000 eq. 34 on the smallest altitude (stable_step.hpp), or the lumped
// system's largest eigenvalue by power iteration (spectral_step.hpp).
enum class CriticalStepMethod { altitude, power_iteration };
const char* critical_step_name(CriticalStepMethod m);

struct ExplicitConfig {
  int steps = 1000;
  std::optional<double> dt;
  double safety_factor = 0.9;
  bool force_dt = false;
  int energy_interval = 100;
  double energy_growth_limit = 2.0;
  // With the automatic step (no dt): steps between re-estimates of the critical step on the
  // deformed mesh (0: never, the step of the undeformed mesh throughout).
  int dt_check_interval = 10;
  // Rigid tools: "grid" (the broad phase, dynamics/contact_search.hpp) or "all" (every node each
  // step; the same results, slower).
  bool contact_search = true;
  CriticalStepMethod critical_step = CriticalStepMethod::altitude;
  // The values the assembled linear rows stream: "double" (default) or "single" (fem/linear_rows.hpp).
  fem::LinearPrecision linear_precision = fem::LinearPrecision::double_precision;
};

struct OutputConfig {
  std::string vtu;
  int vtu_interval = 0;
  io::VtuFormat vtu_format = io::kDefaultVtuFormat;
  std::vector<int> trajectory_nodes;
  int trajectory_interval = 1;
  bool velocity = false;
  bool displacement = true;  // the final displacement field in the artifact
};

struct BenchConfig {
  int steps = 500;
  std::vector<int> threads = {1, 2};
  std::vector<double> linear_fractions = {0.5};  // mixed partitions measured besides the uniform ones
  // --cut-bench (hybrid/cut_bench.hpp): repetitions (best taken) and the nodes of the
  // precomputed-response model (a node set of the mesh).
  int repeats = 5;
  std::vector<int> response_nodes;
};

struct DhdConfig {
  std::string mesh_path;
  std::string model = "neo_hookean_paper";  // as written in the config, or the default
  bool model_defaulted = true;               // material.model left out of the config
  bool linear_material = false;
  fem::Material material;
  double damping_alpha = 0;
  PartitionSpec partition;
  std::string strain_reference;  // path of the strain partition's reference artifact, if any
  bool has_boundary = false;
  dynamics::Scene scene;
  bool static_solver = false;
  ExplicitConfig explicit_solver;
  dynamics::StaticOptions static_options;
  OutputConfig output;
  int threads = 1;
  BenchConfig bench;
  std::vector<CutSpec> cuts;  // explicit runs only
  // Whether the scene may separate along faces (a "separate" cut, or a haptic blade that does):
  // the scene then owns a copy of its mesh, which cuts change, and computes its linear elements
  // element by element (fem::LinearForces::per_element), since an assembled row's pattern
  // cannot follow a node split.
  bool separates = false;
};

// A 3-vector member [x, y, z] of a config object (the scene readers built on this one use it too).
Eigen::Vector3d read_vec3(const io::JsonReader& r, const std::string& key);
// "ramp_time" (s, default 0: full from the start) and "ramp" ("linear" or "smooth") of a load,
// constraint, probe or tool.
dynamics::Ramp read_ramp(const io::JsonReader& r);

// The mesh path alone (the mesh must be loaded before the rest can be read): relative to the
// config file's folder, or else to the working directory (io::JsonReader::get_input_path).
std::string read_mesh_path(const io::JsonReader& config);

// Reads the whole config (calls reject_unknown on every object). A strain partition reads its
// reference `dhd_result` artifact through io::Artifact.
DhdConfig read_dhd_config(const io::JsonReader& config, const mesh::TetMesh& mesh);

}  // namespace softsim::hybrid
