#include "softsim/io/vtu_writer.hpp"

#include <iomanip>
#include <stdexcept>

#include "softsim/io/atomic_file.hpp"

namespace softsim::io {

namespace {
constexpr int kVtkTetra = 10;
}

void write_vtu(const std::string& path, const mesh::TetMesh& mesh, const VtuFields& fields) {
  const std::size_t n = mesh.nodes.size(), m = mesh.tets.size();
  for (const auto& [name, v] : fields.point_vectors)
    if (v.size() != n) throw std::invalid_argument("vtu point field " + name + " has the wrong size");
  for (const auto& [name, v] : fields.point_scalars)
    if (v.size() != n) throw std::invalid_argument("vtu point field " + name + " has the wrong size");
  for (const auto& [name, v] : fields.cell_ints)
    if (v.size() != m) throw std::invalid_argument("vtu cell field " + name + " has the wrong size");
  write_file_atomic(path, [&](std::ostream& out) {
    out << std::setprecision(12);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<UnstructuredGrid>\n"
        << "<Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << m << "\">\n";
    out << "<PointData>\n";
    for (const auto& [name, v] : fields.point_vectors) {
      out << "<DataArray type=\"Float64\" Name=\"" << name << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
      for (const auto& x : v) out << x.x() << ' ' << x.y() << ' ' << x.z() << '\n';
      out << "</DataArray>\n";
    }
    for (const auto& [name, v] : fields.point_scalars) {
      out << "<DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n";
      for (double x : v) out << x << '\n';
      out << "</DataArray>\n";
    }
    out << "</PointData>\n<CellData>\n";
    for (const auto& [name, v] : fields.cell_ints) {
      out << "<DataArray type=\"Int32\" Name=\"" << name << "\" format=\"ascii\">\n";
      for (int x : v) out << x << '\n';
      out << "</DataArray>\n";
    }
    out << "</CellData>\n<Points>\n"
        << "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const auto& x : mesh.nodes) out << x.x() << ' ' << x.y() << ' ' << x.z() << '\n';
    out << "</DataArray>\n</Points>\n<Cells>\n"
        << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const auto& t : mesh.tets) out << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << '\n';
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t e = 0; e < m; ++e) out << 4 * (e + 1) << '\n';
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t e = 0; e < m; ++e) out << kVtkTetra << '\n';
    out << "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  });
}

}  // namespace softsim::io
