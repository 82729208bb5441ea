#include "softsim/hybrid/result_vtu.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace softsim::hybrid {

namespace {
std::string stem_of(const std::string& vtu) {
  return vtu.size() > 4 && vtu.compare(vtu.size() - 4, 4, ".vtu") == 0 ? vtu.substr(0, vtu.size() - 4) : vtu;
}
}  // namespace

ResultVtu::ResultVtu(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds,
                     const fem::Material& material, io::VtuFormat format)
    : mesh_(mesh), format_(format), stress_(mesh, kinds, material) {
  const std::size_t n = mesh.nodes.size(), m = mesh.tets.size();
  fields_.point_vectors["displacement"].resize(n);
  fields_.point_vectors["velocity"].assign(n, Eigen::Vector3d::Zero());
  auto& kind = fields_.cell_ints["element_kind"];
  for (auto k : kinds) kind.push_back(static_cast<int>(k));
  const auto region = mesh.element_tags.find("region");
  fields_.cell_ints["region"] = region != mesh.element_tags.end() ? region->second : std::vector<int>(m, 0);
  fields_.cell_tensors["green_lagrange_strain"].resize(m);
  fields_.cell_tensors["cauchy_stress"].resize(m);
  fields_.cell_scalars["von_mises_stress"].resize(m);
}

void ResultVtu::write(const std::string& path, const std::vector<double>& u, const std::vector<double>& v,
                      const std::function<bool(int)>& removed) {
  auto& du = fields_.point_vectors["displacement"];
  auto& dv = fields_.point_vectors["velocity"];
  for (std::size_t i = 0; i < du.size(); ++i) {
    du[i] = Eigen::Vector3d(u[3 * i], u[3 * i + 1], u[3 * i + 2]);
    dv[i] = v.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
  }
  stress_.evaluate(u.data());
  auto& strain = fields_.cell_tensors["green_lagrange_strain"];
  auto& stress = fields_.cell_tensors["cauchy_stress"];
  auto& von_mises = fields_.cell_scalars["von_mises_stress"];
  for (std::size_t e = 0; e < strain.size(); ++e) {
    strain[e] = io::symmetric_components(stress_.strain()[e]);
    stress[e] = io::symmetric_components(stress_.stress()[e]);
    von_mises[e] = stress_.von_mises()[e];
  }
  if (removed) {
    auto& flag = fields_.cell_ints["removed"];
    flag.assign(strain.size(), 0);
    for (std::size_t e = 0; e < strain.size(); ++e)
      if (removed(static_cast<int>(e))) {
        flag[e] = 1;
        strain[e] = stress[e] = io::symmetric_components(Eigen::Matrix3d::Zero());
        von_mises[e] = 0.0;
      }
  }
  io::write_vtu(path, mesh_, fields_, format_);
}

std::string snapshot_path(const std::string& vtu, int step) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%06d.vtu", step);
  return stem_of(vtu) + buf;
}

std::string series_path(const std::string& vtu) { return stem_of(vtu) + ".pvd"; }

VtuOutput::VtuOutput(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds, const DhdConfig& config)
    : kinds_(kinds), material_(config.material), output_(config.output), has_cuts_(!config.cuts.empty()) {
  if (!output_.vtu.empty()) writer_.emplace(mesh, kinds, config.material, output_.vtu_format);
  written_nodes_ = mesh.num_nodes();
}

ResultVtu& VtuOutput::writer_for(const mesh::TetMesh& mesh) {
  if (mesh.num_nodes() != written_nodes_) {
    writer_.emplace(mesh, kinds_, material_, output_.vtu_format);
    written_nodes_ = mesh.num_nodes();
  }
  return *writer_;
}

dynamics::SnapshotFn VtuOutput::snapshot() {
  if (!writer_ || output_.vtu_interval <= 0) return {};
  return [this](int step, double time, const std::vector<double>& u, const std::vector<double>& v) {
    write_snapshot(step, time, u, v);
  };
}

void VtuOutput::write_snapshot(int step, double time, const std::vector<double>& u, const std::vector<double>& v) {
  const std::string path = snapshot_path(output_.vtu, step);
  (scene_ ? writer_for(scene_->mesh()) : *writer_).write(path, u, v, removed());
  // The .pvd sits beside the snapshots and names them relative to itself.
  series_.push_back({time, std::filesystem::path(path).filename().string()});
  io::write_pvd(series_path(output_.vtu), series_);
}

void VtuOutput::write_final(const DhdRun& run) {
  if (!writer_) return;
  const std::vector<double>& u =
      run.explicit_result ? run.explicit_result->displacement : run.static_result->displacement;
  static const std::vector<double> kNoVelocity;
  const std::vector<int>& gone = run.removed_elements;
  const std::function<bool(int)> removed =
      has_cuts_ ? std::function<bool(int)>([&gone](int e) { return std::binary_search(gone.begin(), gone.end(), e); })
                : std::function<bool(int)>();
  (run.cut_mesh ? writer_for(*run.cut_mesh) : *writer_)
      .write(output_.vtu, u, run.explicit_result ? run.explicit_result->velocity : kNoVelocity, removed);
}

std::function<bool(int)> VtuOutput::removed() const {
  if (!has_cuts_ || !scene_) return {};
  const DhdScene* scene = scene_;
  return [scene](int e) { return scene->removed(e); };
}

}  // namespace softsim::hybrid
