#pragma once
// The material block's members for the laws with more than F (material/transversely_isotropic,
// material/viscoelastic): their config keys are documented in cpp/apps/dhd_sim.md (material).
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "softsim/io/json_reader.hpp"
#include "softsim/material/viscoelastic.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::hybrid {

// "mu" > 0, "eta" >= 0, "K" > 0 and "fibre" (3 numbers, normalised; default x).
material::TransverselyIsotropic read_transversely_isotropic(const io::JsonReader& m);

// "fibre_regions": [{"tag": name, "values": [int...], "fibre": [x, y, z]}, ...]: the elements
// of `mesh` whose element tag `tag` takes one of `values` get that direction, later entries
// over earlier ones; every other element keeps `fibre`. Null when the member is absent.
std::shared_ptr<const std::vector<Eigen::Vector3d>> read_fibre_regions(const io::JsonReader& m,
                                                                       const mesh::TetMesh& mesh,
                                                                       const Eigen::Vector3d& fibre);

// "prony": {"g": [g_1..g_N], "tau": [tau_1..tau_N]} (N = 1..4, g_i >= 0, sum g_i < 1, tau_i > 0 s)
// on `base`.
material::Viscoelastic read_prony(const io::JsonReader& prony, const material::ElasticLaw& base);

}  // namespace softsim::hybrid
