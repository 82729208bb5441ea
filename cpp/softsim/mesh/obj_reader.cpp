#include "softsim/mesh/obj_reader.hpp"

#include <cstdlib>
#include <sstream>

#include "softsim/io/errors.hpp"

namespace softsim::mesh {

TriangleSurface read_obj(const std::string& text, const std::string& source) {
  TriangleSurface s;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  auto fail = [&](const std::string& what) {
    throw InputError(source + ": line " + std::to_string(line_no) + ": expected " + what);
  };
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string kind;
    ls >> kind;
    if (kind == "v") {
      Eigen::Vector3d x;
      if (!(ls >> x[0] >> x[1] >> x[2]) || !x.allFinite()) fail("\"v x y z\" with finite coordinates");
      s.vertices.push_back(x);
    } else if (kind == "f") {
      std::vector<int> idx;
      std::string token;
      while (ls >> token) {
        const long i = std::strtol(token.substr(0, token.find('/')).c_str(), nullptr, 10);
        const long n = static_cast<long>(s.vertices.size());
        const long resolved = i < 0 ? n + i : i - 1;
        if (i == 0 || resolved < 0 || resolved >= n) fail("a vertex index in range, got \"" + token + "\"");
        idx.push_back(static_cast<int>(resolved));
      }
      if (idx.size() < 3) fail("a face of 3 or more vertices");
      for (std::size_t k = 1; k + 1 < idx.size(); ++k) s.triangles.push_back({idx[0], idx[k], idx[k + 1]});
    }
  }
  if (s.triangles.empty()) throw InputError(source + ": expected a closed triangle surface, got no faces");
  return s;
}

}  // namespace softsim::mesh
