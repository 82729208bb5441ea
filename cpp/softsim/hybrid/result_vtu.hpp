#pragma once
// The ParaView output of a dhd_sim run (output.vtu, output.vtu_interval, output.vtu_format;
// cpp/apps/dhd_sim.md): the final state as one VTU file, the explicit run's snapshots as
// <stem>_<step>.vtu files and the <stem>.pvd series that lists them with their times.
//
// Point data: displacement (m), velocity (m/s; zero for the static solver).
// Cell data: element_kind (the codes of fem::kElementKinds), region (the mesh's tag, or
// 0), green_lagrange_strain (E = ½(FᵀF − I), dimensionless), cauchy_stress (Pa, each element's
// own law, fem/element_stress.hpp), both symmetric tensors of 6 components (xx yy zz xy yz xz),
// and von_mises_stress (Pa). Positions are the reference nodes. With cuts: cell data `removed`
// (1: a cut removed the element by then; its strain and stress are written as zero), so
// ParaView's Threshold (removed = 0) shows the cut open.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/fem/element_stress.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/hybrid/dhd_run.hpp"
#include "softsim/io/vtu_writer.hpp"

namespace softsim::hybrid {

// One state's VTU files. The field buffers and the stress evaluator are sized once, so the
// snapshots of a run reuse them.
class ResultVtu {
 public:
  ResultVtu(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds, const fem::Material& material,
            io::VtuFormat format);
  // u, v: 3 values per node; v may be empty (written as zero). Atomic. `removed(e)`: element e
  // is cut away (empty: none is).
  void write(const std::string& path, const std::vector<double>& u, const std::vector<double>& v,
             const std::function<bool(int)>& removed = {});

 private:
  const mesh::TetMesh& mesh_;
  io::VtuFormat format_;
  fem::ElementStress stress_;
  io::VtuFields fields_;
};

// "<stem>_<step>.vtu" (six digits, e.g. _000100) and "<stem>.pvd", the stem being `vtu` less a
// ".vtu" ending.
std::string snapshot_path(const std::string& vtu, int step);
std::string series_path(const std::string& vtu);

// What dhd_sim writes besides its artifact: nothing without output.vtu; otherwise the final
// state, and with output.vtu_interval the snapshots, each followed by the .pvd rewritten
// (atomically) to list every snapshot written so far, so that the series on disk is always whole.
class VtuOutput {
 public:
  VtuOutput(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds, const DhdConfig& config);
  // For run_dhd: empty unless snapshots are asked for. Refers to this object.
  dynamics::SnapshotFn snapshot();
  void write_final(const DhdRun& run);
  // The scene whose cuts the files show (null: none; the scene must outlive the writes).
  void follow_cuts(const DhdScene& scene) { scene_ = &scene; }
  void follow_cuts(std::nullptr_t) { scene_ = nullptr; }

 private:
  void write_snapshot(int step, double time, const std::vector<double>& u, const std::vector<double>& v);

  std::function<bool(int)> removed() const;
  // The writer for `mesh` (rebuilt when separating cuts have added nodes since the last write).
  ResultVtu& writer_for(const mesh::TetMesh& mesh);

  std::vector<fem::ElementKind> kinds_;
  fem::Material material_;
  int written_nodes_ = 0;  // nodes of the mesh the writer was built for
  OutputConfig output_;
  bool has_cuts_ = false;
  const DhdScene* scene_ = nullptr;
  std::optional<ResultVtu> writer_;
  std::vector<io::PvdEntry> series_;
};

}  // namespace softsim::hybrid
