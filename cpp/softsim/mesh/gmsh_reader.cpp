#include "softsim/mesh/gmsh_reader.hpp"

#include <map>
#include <unordered_map>

#include "softsim/io/errors.hpp"
#include "softsim/mesh/text_tokens.hpp"

namespace softsim::mesh {

namespace {

constexpr int kGmshTet4 = 4;

// Number of nodes of Gmsh element types (enough to skip the ones we do not keep).
int gmsh_nodes_per_element(int type, TextTokens& tok) {
  switch (type) {
    case 1: return 2;   case 2: return 3;   case 3: return 4;  case 4: return 4;
    case 5: return 8;   case 6: return 6;   case 7: return 5;  case 8: return 3;
    case 9: return 6;   case 10: return 9;  case 11: return 10; case 12: return 27;
    case 13: return 18; case 14: return 14; case 15: return 1; case 16: return 8;
    case 17: return 20; case 18: return 15; case 19: return 13;
    default: tok.fail("a known Gmsh element type", std::to_string(type));
  }
}

struct Builder {
  std::unordered_map<std::int64_t, int> index_of_id;
  TetMesh mesh;
  std::vector<int> physical;

  void add_node(std::int64_t id, const Eigen::Vector3d& x, TextTokens& tok) {
    if (!index_of_id.emplace(id, mesh.num_nodes()).second)
      tok.fail("a unique node id", "duplicate id " + std::to_string(id));
    mesh.nodes.push_back(x);
  }
  // Keeps a 4-node tetrahedron (other element types are read and dropped by the callers).
  void add_tet(const std::vector<std::int64_t>& ids, int phys, TextTokens& tok) {
    mesh.tets.push_back({index(ids[0], tok), index(ids[1], tok), index(ids[2], tok), index(ids[3], tok)});
    physical.push_back(phys);
  }
  int index(std::int64_t id, TextTokens& tok) const {
    auto it = index_of_id.find(id);
    if (it == index_of_id.end()) tok.fail("a node id defined in the node block", std::to_string(id));
    return it->second;
  }
  TetMesh finish(const std::string& source) {
    if (mesh.tets.empty())
      throw InputError(source + ": expected at least one 4-node tetrahedron, got none");
    mesh.element_tags["physical"] = physical;
    mesh.element_tags["region"] = physical;
    drop_unused_nodes(mesh);
    return std::move(mesh);
  }
};

TetMesh read_v1(TextTokens& tok, const std::string& source) {
  Builder b;
  tok.expect("$NOD");
  const auto n = tok.next_count("node count");
  if (n < 0) tok.fail("a non-negative node count", std::to_string(n));
  for (std::int64_t i = 0; i < n; ++i) {
    const auto id = tok.next_int("node id");
    Eigen::Vector3d x;
    for (int c = 0; c < 3; ++c) x[c] = tok.next_double("a coordinate");
    b.add_node(id, x, tok);
  }
  tok.expect("$ENDNOD");
  tok.expect("$ELM");
  const auto m = tok.next_count("element count");
  for (std::int64_t i = 0; i < m; ++i) {
    tok.next_int("element id");
    const int type = static_cast<int>(tok.next_int("element type"));
    const int phys = static_cast<int>(tok.next_int("physical region"));
    tok.next_int("elementary region");
    const auto nn = tok.next_count("number of nodes");
    if (nn != gmsh_nodes_per_element(type, tok)) tok.fail("the node count of the element type", std::to_string(nn));
    std::vector<std::int64_t> ids(static_cast<std::size_t>(nn));
    for (auto& id : ids) id = tok.next_int("node id");
    if (type == kGmshTet4) b.add_tet(ids, phys, tok);
  }
  tok.expect("$ENDELM");
  return b.finish(source);
}

void skip_section(TextTokens& tok, const std::string& name) {
  const std::string end = "$End" + name.substr(1);
  while (true) {
    const std::string t = tok.next("\"" + end + "\"");
    if (t == end) return;
  }
}

TetMesh read_v2(TextTokens& tok, const std::string& source) {
  Builder b;
  bool have_nodes = false;
  while (!tok.at_end()) {
    const std::string section = tok.next("a section name");
    if (section == "$Nodes") {
      const auto n = tok.next_count("node count");
      for (std::int64_t i = 0; i < n; ++i) {
        const auto id = tok.next_int("node id");
        Eigen::Vector3d x;
        for (int c = 0; c < 3; ++c) x[c] = tok.next_double("a coordinate");
        b.add_node(id, x, tok);
      }
      tok.expect("$EndNodes");
      have_nodes = true;
    } else if (section == "$Elements") {
      if (!have_nodes) tok.fail("$Nodes before $Elements", section);
      const auto m = tok.next_count("element count");
      for (std::int64_t i = 0; i < m; ++i) {
        tok.next_int("element id");
        const int type = static_cast<int>(tok.next_int("element type"));
        const auto ntags = tok.next_count("tag count");
        int phys = 0;
        for (std::int64_t t = 0; t < ntags; ++t) {
          const auto v = tok.next_int("tag");
          if (t == 0) phys = static_cast<int>(v);
        }
        const int nn = gmsh_nodes_per_element(type, tok);
        std::vector<std::int64_t> ids(static_cast<std::size_t>(nn));
        for (auto& id : ids) id = tok.next_int("node id");
        if (type == kGmshTet4) b.add_tet(ids, phys, tok);
      }
      tok.expect("$EndElements");
    } else if (!section.empty() && section[0] == '$') {
      skip_section(tok, section);
    } else {
      tok.fail("a section name starting with $", section);
    }
  }
  return b.finish(source);
}

// Physical tags of the volume entities, from $Entities (4.1).
std::map<int, int> read_entities_v4(TextTokens& tok) {
  std::map<int, int> volume_physical;
  const auto np = tok.next_count("point entity count");
  const auto nc = tok.next_count("curve entity count");
  const auto ns = tok.next_count("surface entity count");
  const auto nv = tok.next_count("volume entity count");
  for (std::int64_t i = 0; i < np; ++i) {
    tok.next_int("point tag");
    for (int c = 0; c < 3; ++c) tok.next_double("a coordinate");
    const auto nphys = tok.next_count("physical tag count");
    for (std::int64_t p = 0; p < nphys; ++p) tok.next_int("physical tag");
  }
  auto read_bounded = [&](std::int64_t count, bool volume) {
    for (std::int64_t i = 0; i < count; ++i) {
      const int tag = static_cast<int>(tok.next_int("entity tag"));
      for (int c = 0; c < 6; ++c) tok.next_double("a bounding-box coordinate");
      const auto nphys = tok.next_count("physical tag count");
      for (std::int64_t p = 0; p < nphys; ++p) {
        const int phys = static_cast<int>(tok.next_int("physical tag"));
        if (volume && p == 0) volume_physical[tag] = phys;
      }
      const auto nbound = tok.next_count("bounding entity count");
      for (std::int64_t k = 0; k < nbound; ++k) tok.next_int("bounding entity tag");
    }
  };
  read_bounded(nc, false);
  read_bounded(ns, false);
  read_bounded(nv, true);
  tok.expect("$EndEntities");
  return volume_physical;
}

TetMesh read_v4(TextTokens& tok, const std::string& source) {
  Builder b;
  std::map<int, int> volume_physical;
  bool have_nodes = false;
  while (!tok.at_end()) {
    const std::string section = tok.next("a section name");
    if (section == "$Entities") {
      volume_physical = read_entities_v4(tok);
    } else if (section == "$Nodes") {
      const auto blocks = tok.next_count("node block count");
      tok.next_count("node count");
      tok.next_int("minimum node tag");
      tok.next_int("maximum node tag");
      for (std::int64_t blk = 0; blk < blocks; ++blk) {
        tok.next_int("entity dimension");
        tok.next_int("entity tag");
        const auto parametric = tok.next_int("parametric flag");
        if (parametric != 0) tok.fail("non-parametric nodes (parametric flag 0)", std::to_string(parametric));
        const auto n = tok.next_count("nodes in block");
        std::vector<std::int64_t> ids(static_cast<std::size_t>(n));
        for (auto& id : ids) id = tok.next_int("node tag");
        for (std::int64_t i = 0; i < n; ++i) {
          Eigen::Vector3d x;
          for (int c = 0; c < 3; ++c) x[c] = tok.next_double("a coordinate");
          b.add_node(ids[static_cast<std::size_t>(i)], x, tok);
        }
      }
      tok.expect("$EndNodes");
      have_nodes = true;
    } else if (section == "$Elements") {
      if (!have_nodes) tok.fail("$Nodes before $Elements", section);
      const auto blocks = tok.next_count("element block count");
      tok.next_count("element count");
      tok.next_int("minimum element tag");
      tok.next_int("maximum element tag");
      for (std::int64_t blk = 0; blk < blocks; ++blk) {
        tok.next_int("entity dimension");
        const int entity = static_cast<int>(tok.next_int("entity tag"));
        const int type = static_cast<int>(tok.next_int("element type"));
        const auto n = tok.next_count("elements in block");
        const int nn = gmsh_nodes_per_element(type, tok);
        const auto phys_it = volume_physical.find(entity);
        const int phys = phys_it == volume_physical.end() ? 0 : phys_it->second;
        for (std::int64_t i = 0; i < n; ++i) {
          tok.next_int("element tag");
          std::vector<std::int64_t> ids(static_cast<std::size_t>(nn));
          for (auto& id : ids) id = tok.next_int("node tag");
          if (type == kGmshTet4) b.add_tet(ids, phys, tok);
        }
      }
      tok.expect("$EndElements");
    } else if (!section.empty() && section[0] == '$') {
      skip_section(tok, section);
    } else {
      tok.fail("a section name starting with $", section);
    }
  }
  return b.finish(source);
}

}  // namespace

TetMesh read_gmsh(const std::string& text, const std::string& source) {
  TextTokens tok(text, source);
  const std::string first = tok.peek();
  if (first == "$NOD") return read_v1(tok, source);
  if (first != "$MeshFormat") tok.fail("a Gmsh mesh ($MeshFormat or $NOD)", first);
  tok.next("$MeshFormat");
  const std::string version = tok.next("a format version");
  const auto file_type = tok.next_int("file type");
  tok.next_int("data size");
  if (file_type != 0) tok.fail("an ASCII mesh (file type 0)", "binary file type " + std::to_string(file_type));
  tok.expect("$EndMeshFormat");
  if (version.rfind("2.", 0) == 0) return read_v2(tok, source);
  if (version == "4.1") return read_v4(tok, source);
  tok.fail("format version 1.0, 2.2 or 4.1", version);
}

}  // namespace softsim::mesh
