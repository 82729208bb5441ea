#pragma once
// The mesher configuration (cpp/apps/mesher.md): a cuboid of 5-tet cells or a mesh file, read
// strictly, and the "tet_mesh" payload mesher writes. Shared by the mesher executable and the
// Python API, so that both build the same mesh from the same config and write the same artifact.
#include <string>

#include <nlohmann/json.hpp>

#include "softsim/io/json_reader.hpp"
#include "softsim/io/mesh_files.hpp"
#include "softsim/io/vtu_writer.hpp"
#include "softsim/mesh/cuboid.hpp"
#include "softsim/mesh/quality.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::io {

struct MesherConfig {
  bool from_file = false;   // source.kind "file" (else "cuboid")
  mesh::CuboidSpec cuboid;  // source.kind "cuboid"
  std::string path;         // source.kind "file": the mesh file, an input of the run
  MeshFileOptions file;
  double sliver_threshold_deg = 5.0;
  std::string vtu;           // optional ParaView file ("" = none)
  VtuFormat vtu_format = kDefaultVtuFormat;
  nlohmann::json source;     // the payload's "source" member
};

// Memory a cuboid mesh takes per node and per tetrahedron while its artifact is made (the mesh,
// the JSON value, its text and the check of what was built; measured peak of a 60^3 cuboid:
// 570 MiB), for the estimate checked before anything is built.
inline constexpr double kMeshBytesPerNode = 400;
inline constexpr double kMeshBytesPerTet = 450;

// Reads the whole config (calls reject_unknown on every object) without touching any file.
MesherConfig read_mesher_config(const JsonReader& config);

// Builds the cuboid or imports the file (InputError on a malformed file).
mesh::TetMesh build_mesh(const MesherConfig& config);

// The "tet_mesh" payload: the mesh, its quality report and where it came from.
nlohmann::json mesher_payload(const mesh::TetMesh& mesh, const mesh::QualityReport& quality,
                              const nlohmann::json& source);

// Reads `payload` back with the checks every reader of a tet_mesh artifact applies (io/
// mesh_artifact.hpp), so that mesher never writes a mesh its readers refuse (tetrahedra of zero
// volume from sizes of 1e-300, or from an origin of 1e20 with a small size): an InputError
// naming the config's /source and the reader's complaint.
void check_built_mesh(const nlohmann::json& payload, const std::string& config_path);

// The mesh as a ParaView file with its element tags as cell data (the config's "vtu").
void write_mesher_vtu(const std::string& path, const mesh::TetMesh& mesh, VtuFormat format = kDefaultVtuFormat);

}  // namespace softsim::io
