#pragma once
// The "cuts" of a dhd_sim config (issue 19, cutting by element removal):
//   "cuts": [{"time": t, "from": [[ax, ay, az], [bx, by, bz]], "to": [[...], [...]],
//             "mode": "remove"}, ...]
// At time t (s) the blade edge a–b sweeps from its `from` position to its `to` position, and
// the elements the swept surface crosses in the deformed geometry are removed.
#include <vector>

#include "softsim/cutting/blade.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::hybrid {

struct CutSpec {
  double time = 0;
  cutting::BladeSweep sweep;
};

// Reads and checks config["cuts"] (absent: none): times non-negative and ascending, each sweep
// sound (cutting::sweep_problem) and crossing at least one element of the undeformed mesh.
std::vector<CutSpec> read_cuts(const io::JsonReader& config, const mesh::TetMesh& mesh);

}  // namespace softsim::hybrid
