#include "softsim/hybrid/dhd_vtu.hpp"

#include <cstdio>

#include "softsim/io/vtu_writer.hpp"

namespace softsim::hybrid {

namespace {

io::VtuFields vtu_fields(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds,
                         const std::vector<double>& u, const std::vector<double>& v) {
  io::VtuFields f;
  auto& du = f.point_vectors["displacement"];
  auto& dv = f.point_vectors["velocity"];
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    du.emplace_back(u[3 * i], u[3 * i + 1], u[3 * i + 2]);
    dv.emplace_back(v.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(v[3 * i], v[3 * i + 1], v[3 * i + 2]));
  }
  auto& kind = f.cell_ints["element_kind"];
  for (auto k : kinds) kind.push_back(static_cast<int>(k));
  const auto region = mesh.element_tags.find("region");
  f.cell_ints["region"] = region != mesh.element_tags.end() ? region->second : std::vector<int>(mesh.num_tets(), 0);
  return f;
}

std::string snapshot_path(const std::string& vtu, int step) {
  const std::string stem = vtu.size() > 4 && vtu.substr(vtu.size() - 4) == ".vtu" ? vtu.substr(0, vtu.size() - 4) : vtu;
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%06d.vtu", step);
  return stem + buf;
}

}  // namespace

DhdRun run_dhd_writing_vtu(const mesh::TetMesh& mesh, const DhdConfig& config, const dynamics::ProgressFn& progress) {
  const std::vector<fem::ElementKind> kinds = make_partition(mesh, config.partition);
  dynamics::SnapshotFn snapshot;
  if (!config.output.vtu.empty() && config.output.vtu_interval > 0)
    snapshot = [&](int step, double, const std::vector<double>& u, const std::vector<double>& v) {
      io::write_vtu(snapshot_path(config.output.vtu, step), mesh, vtu_fields(mesh, kinds, u, v));
    };
  DhdRun run = run_dhd(mesh, config, kinds, snapshot, progress);
  if (!config.output.vtu.empty()) {
    const std::vector<double>& u =
        run.explicit_result ? run.explicit_result->displacement : run.static_result->displacement;
    const std::vector<double> v = run.explicit_result ? run.explicit_result->velocity : std::vector<double>();
    io::write_vtu(config.output.vtu, mesh, vtu_fields(mesh, run.kinds, u, v));
  }
  return run;
}

}  // namespace softsim::hybrid
