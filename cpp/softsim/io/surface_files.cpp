#include "softsim/io/surface_files.hpp"

#include <cctype>
#include <filesystem>

#include "softsim/io/atomic_file.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/mesh/stl_reader.hpp"

namespace softsim::io {

mesh::TriangleSurface read_surface_file(const std::string& path, double scale) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".stl" && ext != ".obj")
    throw InputError(path + ": expected a closed triangle surface file (.stl or .obj), got extension \"" + ext + "\"");
  const std::string bytes = read_text_file(path);
  mesh::TriangleSurface s = ext == ".stl" ? mesh::read_stl(bytes, path) : mesh::read_obj(bytes, path);
  for (auto& v : s.vertices) v *= scale;
  return s;
}

}  // namespace softsim::io
