#pragma once
// `dhd_sim --cut-bench`: what a topology change costs (issue 19, 000's claim measured). On the
// config's mesh, partition, scene and first cut (taken on the undeformed mesh):
//   * the explicit engine: its one-time set-up, one step, the cut event (finding the crossed
//     elements, the local update) and a full set-up on the cut mesh (what an engine without
//     local updates would redo);
//   * the methods that precompute (000 §1): assembling and factorising the linear stiffness of
//     the cut mesh with its constrained dofs eliminated (Eigen's sparse Cholesky, SimplicialLLT,
//     the implicit solver's work at a topology change), and recomputing a precomputed-response
//     model for the nodes of `cut_bench.response_set` (one solve per dof on that factor).
// Each time is the best of `cut_bench.repeats` repetitions (the machine is shared).
#include <nlohmann/json.hpp>

#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::hybrid {

inline constexpr const char* kCutBenchSchema = "dhd_cut_bench";
inline constexpr int kCutBenchSchemaVersion = 1;

nlohmann::json cut_bench(const mesh::TetMesh& mesh, const DhdConfig& config, int repeats,
                         const std::vector<int>& response_nodes);

}  // namespace softsim::hybrid
