#pragma once
// A dhd_sim run with the ParaView output its config asks for (output.vtu, vtu_interval,
// vtu_format: hybrid/result_vtu.hpp). Shared by dhd_sim and the Python API so that the same
// config writes the same files.
#include "softsim/hybrid/dhd_run.hpp"

namespace softsim::hybrid {

// run_dhd, writing the configured VTU files (none when config.output.vtu is empty); `progress`
// as for run_dhd.
DhdRun run_dhd_writing_vtu(const mesh::TetMesh& mesh, const DhdConfig& config,
                           const dynamics::ProgressFn& progress = {});

}  // namespace softsim::hybrid
