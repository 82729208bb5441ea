#include "softsim/mesh/stl_reader.hpp"

#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>
#include <tuple>

#include "softsim/io/errors.hpp"

namespace softsim::mesh {

namespace {

// Welds corners of equal coordinates into one vertex.
class Welder {
 public:
  explicit Welder(TriangleSurface& s) : s_(s) {}
  int vertex(const Eigen::Vector3d& x) {
    const auto key = std::make_tuple(x[0], x[1], x[2]);
    const auto it = index_.find(key);
    if (it != index_.end()) return it->second;
    s_.vertices.push_back(x);
    return index_[key] = static_cast<int>(s_.vertices.size()) - 1;
  }

 private:
  TriangleSurface& s_;
  std::map<std::tuple<double, double, double>, int> index_;
};

TriangleSurface read_binary(const std::string& bytes, std::uint32_t count, const std::string& source) {
  TriangleSurface s;
  Welder weld(s);
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* rec = bytes.data() + 84 + 50 * static_cast<std::size_t>(t);
    Triangle tri;
    for (int c = 0; c < 3; ++c) {
      float v[3];
      std::memcpy(v, rec + 12 + 12 * c, sizeof v);  // little-endian IEEE floats, as the format fixes
      const Eigen::Vector3d x(v[0], v[1], v[2]);
      if (!x.allFinite())
        throw InputError(source + ": triangle " + std::to_string(t) + ": expected finite corner coordinates");
      tri[c] = weld.vertex(x);
    }
    s.triangles.push_back(tri);
  }
  return s;
}

TriangleSurface read_ascii(const std::string& text, const std::string& source) {
  TriangleSurface s;
  Welder weld(s);
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  auto fail = [&](const std::string& what) {
    throw InputError(source + ": line " + std::to_string(line_no) + ": expected " + what);
  };
  Triangle tri{};
  int corners = -1;  // -1: outside a facet
  bool solid = false;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string word;
    if (!(ls >> word)) continue;
    if (!solid) {
      if (word != "solid") fail("\"solid\" to begin an ASCII STL file");
      solid = true;
    } else if (word == "facet") {
      if (corners != -1) fail("\"endfacet\" before the next \"facet\"");
      corners = 0;
    } else if (word == "vertex") {
      if (corners < 0 || corners >= 3) fail("three \"vertex\" lines inside a facet");
      Eigen::Vector3d x;
      if (!(ls >> x[0] >> x[1] >> x[2]) || !x.allFinite()) fail("\"vertex x y z\" with finite coordinates");
      tri[corners++] = weld.vertex(x);
    } else if (word == "endfacet") {
      if (corners != 3) fail("a facet of three vertices");
      s.triangles.push_back(tri);
      corners = -1;
    } else if (word == "endsolid") {
      if (corners != -1) fail("\"endfacet\" before \"endsolid\"");
    } else if (word != "outer" && word != "endloop" && word != "solid") {
      fail("an STL keyword (facet, outer loop, vertex, endloop, endfacet, endsolid), got \"" + word + "\"");
    }
  }
  if (corners != -1) fail("\"endfacet\" before the end of the file");
  return s;
}

}  // namespace

TriangleSurface read_stl(const std::string& bytes, const std::string& source) {
  TriangleSurface s;
  std::uint32_t count = 0;
  if (bytes.size() >= 84) std::memcpy(&count, bytes.data() + 80, sizeof count);
  if (bytes.size() >= 84 && bytes.size() == 84 + 50 * static_cast<std::uint64_t>(count)) {
    s = read_binary(bytes, count, source);
  } else if (const std::size_t first = bytes.find_first_not_of(" \t\r\n");
             first != std::string::npos && bytes.compare(first, 5, "solid") == 0) {
    s = read_ascii(bytes, source);
  } else {
    throw InputError(source + ": expected an STL file (ASCII beginning with \"solid\", or binary of 84 + 50 x " +
                     std::to_string(count) + " bytes), got " + std::to_string(bytes.size()) + " bytes");
  }
  if (s.triangles.empty()) throw InputError(source + ": expected a closed triangle surface, got no triangles");
  return s;
}

}  // namespace softsim::mesh
