#pragma once
// Nodal fields read back from a dhd_sim "dhd_result" artifact, for the tools that build on a
// computed solution (a strain-based partition, a series of static solutions to fit).
#include <string>
#include <vector>

#include "softsim/io/artifact.hpp"

namespace softsim::io {

// The result's payload.displacement as 3 values per node (ux, uy, uz, m). InputError naming the
// file and JSON pointer unless it holds one [ux, uy, uz] per node of the `num_nodes`-node mesh;
// `mesh_name`, when given, is named in that message.
std::vector<double> read_nodal_displacements(const Artifact& result, int num_nodes, const std::string& mesh_name = "");

}  // namespace softsim::io
