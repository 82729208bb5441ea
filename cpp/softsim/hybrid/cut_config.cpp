#include "softsim/hybrid/cut_config.hpp"


namespace softsim::hybrid {

namespace {

Eigen::Vector3d read_point(const io::JsonReader& p) {
  if (!p.raw().is_array() || p.size() != 3) p.fail("a point [x, y, z] (m)");
  return Eigen::Vector3d(p[0].as_double(), p[1].as_double(), p[2].as_double());
}

// [[ax, ay, az], [bx, by, bz]]: the blade edge's two ends.
void read_edge(const io::JsonReader& cut, const std::string& key, Eigen::Vector3d& a, Eigen::Vector3d& b) {
  const io::JsonReader edge = cut.at(key);
  if (!edge.raw().is_array() || edge.size() != 2) edge.fail("the blade edge's two ends [[ax, ay, az], [bx, by, bz]]");
  a = read_point(edge[0]);
  b = read_point(edge[1]);
}

}  // namespace

std::vector<CutSpec> read_cuts(const io::JsonReader& config, const mesh::TetMesh& mesh) {
  std::vector<CutSpec> cuts;
  const auto list = config.optional("cuts");
  if (!list) return cuts;
  if (!list->raw().is_array()) list->fail("a list of cuts");
  for (std::size_t k = 0; k < list->size(); ++k) {
    const io::JsonReader c = (*list)[k];
    CutSpec cut;
    cut.time = c.get_double("time");
    c.require(cut.time >= 0, "time", "a non-negative time (s)");
    if (!cuts.empty()) c.require(cut.time >= cuts.back().time, "time", "cut times in ascending order");
    cut.mode = c.get_choice("mode", {"remove", "separate"}, "remove") == "separate" ? CutMode::separate : CutMode::remove;
    read_edge(c, "from", cut.sweep.a0, cut.sweep.b0);
    read_edge(c, "to", cut.sweep.a1, cut.sweep.b1);
    const std::string problem = cutting::sweep_problem(cut.sweep);
    if (!problem.empty()) c.fail(problem);
    if (cutting::elements_crossed(mesh, nullptr, cut.sweep).empty())
      c.fail("a blade sweep that crosses the mesh (this one crosses no element of the undeformed mesh)");
    c.reject_unknown();
    cuts.push_back(cut);
  }
  return cuts;
}

}  // namespace softsim::hybrid
