#pragma once
// Strict reading of rpim_precompute's "organ" block (cpp/apps/rpim_precompute.md) and its echo
// into artifacts.
#include <string>

#include <nlohmann/json.hpp>

#include "softsim/io/json_reader.hpp"
#include "softsim/mesh/tet_mesh.hpp"
#include "softsim/meshless/organ_scene.hpp"

namespace softsim::meshless {

// Consumes the block and rejects unknown keys; `mesh` is resolved as an input path.
OrganScene read_organ_scene(const io::JsonReader& block);

// The scene as run: the settings, the mesh's counts, the surface and loaded nodes.
nlohmann::json organ_scene_json(const OrganScene& scene, const mesh::TetMesh& mesh, const SceneLayout& layout);

}  // namespace softsim::meshless

namespace softsim::meshless {

// The resolved mesh path of a config's "organ" block, "" without one (so that a tool records
// the mesh as an input before anything runs).
std::string organ_mesh_path(const io::JsonReader& config);

}  // namespace softsim::meshless
