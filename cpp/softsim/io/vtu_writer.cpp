#include "softsim/io/vtu_writer.hpp"

#include <charconv>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "softsim/io/atomic_file.hpp"
#include "softsim/io/base64.hpp"

namespace softsim::io {

namespace {

constexpr std::uint8_t kVtkTetra = 10;
// The arrays are written from memory as they are, in the machine's byte order.
constexpr const char* kByteOrder = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ ? "LittleEndian" : "BigEndian";
static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "node coordinates are written as contiguous doubles");
static_assert(sizeof(mesh::Tet) == 4 * sizeof(std::int32_t), "connectivity is written from the tets as Int32");

const char* const kTensorComponents[6] = {"XX", "YY", "ZZ", "XY", "YZ", "XZ"};

enum class Type { f64, i32, i64, u8 };

const char* type_name(Type t) {
  switch (t) {
    case Type::f64: return "Float64";
    case Type::i32: return "Int32";
    case Type::i64: return "Int64";
    case Type::u8: return "UInt8";
  }
  return "";
}

std::size_t type_size(Type t) {
  switch (t) {
    case Type::f64: return 8;
    case Type::i32: return 4;
    case Type::i64: return 8;
    case Type::u8: return 1;
  }
  return 0;
}

// One DataArray: `values` scalars of `type` stored contiguously at `data`.
struct Array {
  Type type;
  std::string name;  // empty for the points
  int components = 1;
  const char* const* component_names = nullptr;
  const void* data = nullptr;
  std::size_t values = 0;
  std::uint64_t bytes() const { return values * type_size(type); }
};

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// Shortest decimal text that reads back to the same value (std::to_chars), so an ASCII file
// holds exactly the doubles a binary one does.
void write_ascii_values(std::ostream& out, const Array& a) {
  char buf[40];
  for (std::size_t i = 0; i < a.values; ++i) {
    char* end = buf;
    switch (a.type) {
      case Type::f64: end = std::to_chars(buf, buf + 32, static_cast<const double*>(a.data)[i]).ptr; break;
      case Type::i32: end = std::to_chars(buf, buf + 32, static_cast<const std::int32_t*>(a.data)[i]).ptr; break;
      case Type::i64: end = std::to_chars(buf, buf + 32, static_cast<const std::int64_t*>(a.data)[i]).ptr; break;
      case Type::u8: end = std::to_chars(buf, buf + 32, int(static_cast<const std::uint8_t*>(a.data)[i])).ptr; break;
    }
    *end++ = (i + 1) % static_cast<std::size_t>(a.components) == 0 ? '\n' : ' ';
    out.write(buf, end - buf);
  }
}

void write_array(std::ostream& out, const Array& a, VtuFormat format, std::uint64_t& appended_offset) {
  out << "<DataArray type=\"" << type_name(a.type) << '"';
  if (!a.name.empty()) out << " Name=\"" << xml_escape(a.name) << '"';
  if (a.components != 1) out << " NumberOfComponents=\"" << a.components << '"';
  if (a.component_names)
    for (int c = 0; c < a.components; ++c) out << " ComponentName" << c << "=\"" << a.component_names[c] << '"';
  const std::uint64_t header = a.bytes();
  switch (format) {
    case VtuFormat::ascii:
      out << " format=\"ascii\">\n";
      write_ascii_values(out, a);
      break;
    case VtuFormat::base64: {
      // VTK's uncompressed inline layout: the byte count and the values, base64 as one stream.
      out << " format=\"binary\">\n";
      Base64Writer b64(out);
      b64.put(&header, sizeof header);
      b64.put(a.data, a.bytes());
      b64.finish();
      out << '\n';
      break;
    }
    case VtuFormat::raw:
      out << " format=\"appended\" offset=\"" << appended_offset << "\">\n";
      appended_offset += sizeof header + header;
      break;
  }
  out << "</DataArray>\n";
}

void check_size(std::size_t got, std::size_t want, const char* where, const std::string& name) {
  if (got != want) throw std::invalid_argument(std::string("vtu ") + where + " field " + name + " has the wrong size");
}

}  // namespace

const char* vtu_format_name(VtuFormat format) {
  switch (format) {
    case VtuFormat::ascii: return "ascii";
    case VtuFormat::base64: return "base64";
    case VtuFormat::raw: return "raw";
  }
  return "";
}

std::optional<VtuFormat> parse_vtu_format(const std::string& name) {
  for (VtuFormat f : {VtuFormat::ascii, VtuFormat::base64, VtuFormat::raw})
    if (name == vtu_format_name(f)) return f;
  return std::nullopt;
}

SymmetricTensor symmetric_components(const Eigen::Matrix3d& t) {
  return {t(0, 0), t(1, 1), t(2, 2), t(0, 1), t(1, 2), t(0, 2)};
}

void write_vtu(const std::string& path, const mesh::TetMesh& mesh, const VtuFields& fields, VtuFormat format) {
  const std::size_t n = mesh.nodes.size(), m = mesh.tets.size();
  std::vector<Array> point_data, cell_data;
  for (const auto& [name, v] : fields.point_vectors) {
    check_size(v.size(), n, "point", name);
    point_data.push_back({Type::f64, name, 3, nullptr, v.data(), 3 * n});
  }
  for (const auto& [name, v] : fields.point_scalars) {
    check_size(v.size(), n, "point", name);
    point_data.push_back({Type::f64, name, 1, nullptr, v.data(), n});
  }
  for (const auto& [name, v] : fields.cell_ints) {
    check_size(v.size(), m, "cell", name);
    cell_data.push_back({Type::i32, name, 1, nullptr, v.data(), m});
  }
  for (const auto& [name, v] : fields.cell_scalars) {
    check_size(v.size(), m, "cell", name);
    cell_data.push_back({Type::f64, name, 1, nullptr, v.data(), m});
  }
  for (const auto& [name, v] : fields.cell_tensors) {
    check_size(v.size(), m, "cell", name);
    cell_data.push_back({Type::f64, name, 6, kTensorComponents, v.data(), 6 * m});
  }
  std::vector<std::int64_t> offsets(m);
  for (std::size_t e = 0; e < m; ++e) offsets[e] = static_cast<std::int64_t>(4 * (e + 1));
  const std::vector<std::uint8_t> types(m, kVtkTetra);
  const Array points{Type::f64, "", 3, nullptr, mesh.nodes.data(), 3 * n};
  const std::vector<Array> cells = {{Type::i32, "connectivity", 1, nullptr, mesh.tets.data(), 4 * m},
                                    {Type::i64, "offsets", 1, nullptr, offsets.data(), m},
                                    {Type::u8, "types", 1, nullptr, types.data(), m}};

  write_file_atomic(path, [&](std::ostream& out) {
    std::uint64_t offset = 0;
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"" << kByteOrder
        << "\" header_type=\"UInt64\">\n"
        << "<UnstructuredGrid>\n"
        << "<Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << m << "\">\n";
    out << "<PointData>\n";
    for (const Array& a : point_data) write_array(out, a, format, offset);
    out << "</PointData>\n<CellData>\n";
    for (const Array& a : cell_data) write_array(out, a, format, offset);
    out << "</CellData>\n<Points>\n";
    write_array(out, points, format, offset);
    out << "</Points>\n<Cells>\n";
    for (const Array& a : cells) write_array(out, a, format, offset);
    out << "</Cells>\n</Piece>\n</UnstructuredGrid>\n";
    if (format == VtuFormat::raw) {
      // The blocks in the order their offsets were handed out above.
      out << "<AppendedData encoding=\"raw\">\n_";
      auto block = [&](const Array& a) {
        const std::uint64_t header = a.bytes();
        out.write(reinterpret_cast<const char*>(&header), sizeof header);
        out.write(static_cast<const char*>(a.data), static_cast<std::streamsize>(header));
      };
      for (const Array& a : point_data) block(a);
      for (const Array& a : cell_data) block(a);
      block(points);
      for (const Array& a : cells) block(a);
      out << "\n</AppendedData>\n";
    }
    out << "</VTKFile>\n";
  });
}

void write_pvd(const std::string& path, const std::vector<PvdEntry>& entries) {
  write_file_atomic(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"" << kByteOrder << "\">\n<Collection>\n";
    char buf[32];
    for (const PvdEntry& e : entries) {
      const char* end = std::to_chars(buf, buf + sizeof buf, e.time).ptr;
      out << "<DataSet timestep=\"" << std::string_view(buf, end - buf) << "\" group=\"\" part=\"0\" file=\""
          << xml_escape(e.file) << "\"/>\n";
    }
    out << "</Collection>\n</VTKFile>\n";
  });
}

}  // namespace softsim::io
