#pragma once
// VTK XML UnstructuredGrid (.vtu) export so any mesh or result opens in ParaView, in one of
// three encodings: ASCII, inline base64 and raw appended binary (what ParaView's "Save Data"
// writes by default). Binary arrays carry VTK's UInt64 byte-count header; mesh/vtu_reader.hpp reads all
// three back.
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::io {

enum class VtuFormat {
  ascii,   // text; doubles in their shortest exact decimal form, so they read back bit for bit
  base64,  // format="binary": each array inline as base64 of (UInt64 byte count, values)
  raw,     // format="appended": every array's (UInt64 byte count, values) after <AppendedData
           // encoding="raw">; the smallest and fastest to read, not well-formed XML
};
// "ascii", "base64", "raw".
const char* vtu_format_name(VtuFormat format);
std::optional<VtuFormat> parse_vtu_format(const std::string& name);
inline const std::vector<std::string> kVtuFormatNames = {"ascii", "base64", "raw"};
// What the tools write unless told otherwise: binary (exact and compact), and still well-formed
// XML that every VTU reader takes. Raw appended data is smaller and faster, but XML tools refuse
// it, and meshio (5.x, Debian 12) misreads files with several raw appended arrays: it rewrites
// their offsets in place and can then find an array by another's offset.
inline constexpr VtuFormat kDefaultVtuFormat = VtuFormat::base64;

// A symmetric tensor as VTK stores one in 6 components: xx, yy, zz, xy, yz, xz (the order of
// vtkMath::TensorFromSymmetricTensor, and the component names ParaView shows).
using SymmetricTensor = std::array<double, 6>;
SymmetricTensor symmetric_components(const Eigen::Matrix3d& t);

struct VtuFields {
  std::map<std::string, std::vector<Eigen::Vector3d>> point_vectors;  // e.g. displacement, velocity
  std::map<std::string, std::vector<double>> point_scalars;
  std::map<std::string, std::vector<int>> cell_ints;  // e.g. element kind, region
  std::map<std::string, std::vector<double>> cell_scalars;
  std::map<std::string, std::vector<SymmetricTensor>> cell_tensors;  // e.g. stress, strain
};

// Positions written are the reference nodes (apply the "displacement" vector with
// ParaView's Warp By Vector). Written atomically.
void write_vtu(const std::string& path, const mesh::TetMesh& mesh, const VtuFields& fields, VtuFormat format);

// A ParaView data-set collection (.pvd): one entry per file with its time. `files` are written
// as given (names relative to the .pvd's folder). Written atomically.
struct PvdEntry {
  double time = 0;
  std::string file;
};
void write_pvd(const std::string& path, const std::vector<PvdEntry>& entries);

}  // namespace softsim::io
