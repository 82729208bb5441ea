#pragma once
// The "cuts" of a dhd_sim config (issue 19):
//   "cuts": [{"time": t, "from": [[ax, ay, az], [bx, by, bz]], "to": [[...], [...]],
//             "mode": "remove" | "separate"}, ...]
// At time t (s) the blade edge a–b sweeps from its `from` position to its `to` position. With
// "remove" (the default) the elements the swept surface crosses in the deformed geometry are
// removed; with "separate" the mesh opens along the faces nearest the swept surface by
// duplicating nodes (cutting/separation.hpp), and nothing is removed.
#include <vector>

#include "softsim/cutting/blade.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::hybrid {

enum class CutMode { remove, separate };

struct CutSpec {
  double time = 0;
  cutting::BladeSweep sweep;
  CutMode mode = CutMode::remove;
};

// Reads and checks config["cuts"] (absent: none): times non-negative and ascending, each sweep
// sound (cutting::sweep_problem) and crossing at least one element of the undeformed mesh.
std::vector<CutSpec> read_cuts(const io::JsonReader& config, const mesh::TetMesh& mesh);

}  // namespace softsim::hybrid
