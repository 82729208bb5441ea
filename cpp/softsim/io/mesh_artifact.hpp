#pragma once
// The mesh artifact (schema "tet_mesh" v1): nodes, tets, boundary triangles, node sets,
// element tags and the quality report, all SI.
#include <string>

#include <nlohmann/json.hpp>

#include "softsim/io/json_reader.hpp"
#include "softsim/mesh/quality.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::io {

inline constexpr const char* kMeshSchema = "tet_mesh";
inline constexpr int kMeshSchemaVersion = 1;

nlohmann::json mesh_to_json(const mesh::TetMesh& mesh);
nlohmann::json quality_to_json(const mesh::QualityReport& report);

// Strict: indices in range, no repeated node in a tet, positive volumes, tag sizes equal to
// the element count. Errors name the file and the JSON pointer.
mesh::TetMesh mesh_from_json(const JsonReader& payload);

// Reads a "tet_mesh" artifact.
mesh::TetMesh read_mesh_artifact(const std::string& path);

}  // namespace softsim::io
