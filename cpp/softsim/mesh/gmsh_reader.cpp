#include "softsim/mesh/gmsh_reader.hpp"

#include <climits>
#include <cmath>
#include <cstdint>
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

// The numbers of a 2.2 or 4.1 file, from text tokens or from binary blocks (file type 1), where
// ints are 4 bytes, "size_t" values the $MeshFormat data size, and reals 8-byte doubles, in
// the order the ASCII file lists them. Counts are checked against the bytes left (each item
// takes at least `min_bytes`), so a corrupt count cannot trigger a huge allocation.
class Values {
 public:
  Values(TextTokens& tok, bool binary, int size_bytes) : tok_(tok), binary_(binary), size_bytes_(size_bytes) {}

  bool binary() const { return binary_; }
  // The section's binary data begins after the line just read.
  void start_data() {
    if (binary_) tok_.begin_binary();
  }
  // A Gmsh "int" (4 bytes in a binary file): a text value beyond the 32-bit range is refused
  // rather than narrowed (an element type of 4294967300 is not a tetrahedron).
  int integer(const std::string& what) {
    if (!binary_) return tok_.next_int32(what);
    std::int32_t v;
    tok_.read_bytes(&v, sizeof v, what);
    return v;
  }
  std::int64_t size(const std::string& what) {
    if (!binary_) return tok_.next_int(what);
    if (size_bytes_ == 4) {
      std::uint32_t v;
      tok_.read_bytes(&v, sizeof v, what);
      return v;
    }
    std::uint64_t v;
    tok_.read_bytes(&v, sizeof v, what);
    if (v > static_cast<std::uint64_t>(INT64_MAX)) tok_.fail(what, std::to_string(v));
    return static_cast<std::int64_t>(v);
  }
  double real(const std::string& what) {
    if (!binary_) return tok_.next_double(what);
    double v;
    tok_.read_bytes(&v, sizeof v, what);
    if (!std::isfinite(v)) tok_.fail(what + " (finite)", std::to_string(v));
    return v;
  }
  std::int64_t count(const std::string& what, std::size_t min_bytes) {
    if (!binary_) return tok_.next_count(what);
    const std::int64_t n = size(what);
    if (n < 0 || static_cast<std::uint64_t>(n) > tok_.bytes_left() / min_bytes)
      tok_.fail(what + " (a count the rest of the file can hold)", std::to_string(n));
    return n;
  }
  int int_bytes() const { return 4; }
  int size_bytes() const { return size_bytes_; }
  TextTokens& tokens() { return tok_; }

 private:
  TextTokens& tok_;
  bool binary_;
  int size_bytes_;
};

// n node records "id x y z" of formats 1.0 and 2.2 (binary: an int and 3 doubles).
void read_node_records(Values& in, Builder& b, std::int64_t n) {
  for (std::int64_t i = 0; i < n; ++i) {
    const auto id = in.integer("node id");
    Eigen::Vector3d x;
    for (int c = 0; c < 3; ++c) x[c] = in.real("a coordinate");
    b.add_node(id, x, in.tokens());
  }
}

TetMesh read_v1(TextTokens& tok, const std::string& source) {
  Builder b;
  tok.expect("$NOD");
  Values text(tok, false, 8);
  read_node_records(text, b, tok.next_count("node count"));
  tok.expect("$ENDNOD");
  tok.expect("$ELM");
  const auto m = tok.next_count("element count");
  for (std::int64_t i = 0; i < m; ++i) {
    tok.next_int("element id");
    const int type = tok.next_int32("element type");
    const int phys = tok.next_int32("physical region");
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

// $Nodes of format 2.2: the count on its own line, then the node records.
void read_nodes_v2(Values& in, Builder& b) {
  TextTokens& tok = in.tokens();
  const auto n = tok.next_count("node count");
  in.start_data();
  read_node_records(in, b, n);
  tok.expect("$EndNodes");
}

// $Elements of format 2.2. ASCII: "id type ntags tags... nodes..." per element. Binary: blocks
// of one header (type, number of elements, tags per element) followed by that many
// "id tags... nodes..." records, all ints.
void read_elements_v2(Values& in, Builder& b) {
  TextTokens& tok = in.tokens();
  const auto m = tok.next_count("element count");
  in.start_data();
  std::vector<std::int64_t> ids;
  auto element = [&](int type, std::int64_t ntags) {
    int phys = 0;
    for (std::int64_t t = 0; t < ntags; ++t) {
      const auto v = in.integer("tag");
      if (t == 0) phys = v;
    }
    ids.resize(static_cast<std::size_t>(gmsh_nodes_per_element(type, tok)));
    for (auto& id : ids) id = in.integer("node id");
    if (type == kGmshTet4) b.add_tet(ids, phys, tok);
  };
  if (!in.binary()) {
    for (std::int64_t i = 0; i < m; ++i) {
      in.integer("element id");
      const int type = in.integer("element type");
      element(type, tok.next_count("tag count"));
    }
  } else {
    for (std::int64_t done = 0; done < m;) {
      const int type = in.integer("element type");
      const auto follow = in.integer("number of elements of the block");
      const auto ntags = in.integer("tag count");
      if (follow < 1 || follow > m - done) tok.fail("a block of 1 to " + std::to_string(m - done) + " elements", std::to_string(follow));
      if (ntags < 0 || static_cast<std::uint64_t>(ntags) > tok.bytes_left() / 4) tok.fail("a tag count", std::to_string(ntags));
      for (std::int64_t k = 0; k < follow; ++k) {
        in.integer("element id");
        element(type, ntags);
      }
      done += follow;
    }
  }
  tok.expect("$EndElements");
}

TetMesh read_v2(Values& in, const std::string& source) {
  TextTokens& tok = in.tokens();
  Builder b;
  bool have_nodes = false;
  while (!tok.at_end()) {
    const std::string section = tok.next("a section name");
    if (section == "$Nodes") {
      read_nodes_v2(in, b);
      have_nodes = true;
    } else if (section == "$Elements") {
      if (!have_nodes) tok.fail("$Nodes before $Elements", section);
      read_elements_v2(in, b);
    } else if (!section.empty() && section[0] == '$') {
      skip_section(tok, section);
    } else {
      tok.fail("a section name starting with $", section);
    }
  }
  return b.finish(source);
}

// Physical tags of the volume entities, from $Entities (4.1).
std::map<int, int> read_entities_v4(Values& in) {
  std::map<int, int> volume_physical;
  in.start_data();
  const int ib = in.int_bytes(), sb = in.size_bytes();
  const auto np = in.count("point entity count", ib + 3 * 8 + sb);
  const auto nc = in.count("curve entity count", ib + 6 * 8 + 2 * sb);
  const auto ns = in.count("surface entity count", ib + 6 * 8 + 2 * sb);
  const auto nv = in.count("volume entity count", ib + 6 * 8 + 2 * sb);
  for (std::int64_t i = 0; i < np; ++i) {
    in.integer("point tag");
    for (int c = 0; c < 3; ++c) in.real("a coordinate");
    const auto nphys = in.count("physical tag count", ib);
    for (std::int64_t p = 0; p < nphys; ++p) in.integer("physical tag");
  }
  auto read_bounded = [&](std::int64_t count, bool volume) {
    for (std::int64_t i = 0; i < count; ++i) {
      const int tag = in.integer("entity tag");
      for (int c = 0; c < 6; ++c) in.real("a bounding-box coordinate");
      const auto nphys = in.count("physical tag count", ib);
      for (std::int64_t p = 0; p < nphys; ++p) {
        const int phys = in.integer("physical tag");
        if (volume && p == 0) volume_physical[tag] = phys;
      }
      const auto nbound = in.count("bounding entity count", ib);
      for (std::int64_t k = 0; k < nbound; ++k) in.integer("bounding entity tag");
    }
  };
  read_bounded(nc, false);
  read_bounded(ns, false);
  read_bounded(nv, true);
  in.tokens().expect("$EndEntities");
  return volume_physical;
}

// The header of $Nodes and $Elements (4.1): numEntityBlocks, the item count, the smallest and
// largest tag. Returns the number of blocks (each starts with 3 ints and a size).
std::int64_t block_count(Values& in, const std::string& item) {
  in.start_data();
  const auto blocks = in.count(item + " block count", 3 * in.int_bytes() + in.size_bytes());
  in.size(item + " count");
  in.size("minimum " + item + " tag");
  in.size("maximum " + item + " tag");
  return blocks;
}

void read_nodes_v4(Values& in, Builder& b) {
  TextTokens& tok = in.tokens();
  const int sb = in.size_bytes();
  const auto blocks = block_count(in, "node");
  std::vector<std::int64_t> ids;
  for (std::int64_t blk = 0; blk < blocks; ++blk) {
    in.integer("entity dimension");
    in.integer("entity tag");
    const auto parametric = in.integer("parametric flag");
    if (parametric != 0) tok.fail("non-parametric nodes (parametric flag 0)", std::to_string(parametric));
    const auto n = in.count("nodes in block", sb + 3 * 8);
    ids.resize(static_cast<std::size_t>(n));
    for (auto& id : ids) id = in.size("node tag");
    for (std::int64_t i = 0; i < n; ++i) {
      Eigen::Vector3d x;
      for (int c = 0; c < 3; ++c) x[c] = in.real("a coordinate");
      b.add_node(ids[static_cast<std::size_t>(i)], x, tok);
    }
  }
  tok.expect("$EndNodes");
}

void read_elements_v4(Values& in, Builder& b, const std::map<int, int>& volume_physical) {
  TextTokens& tok = in.tokens();
  const int sb = in.size_bytes();
  const auto blocks = block_count(in, "element");
  std::vector<std::int64_t> ids;
  for (std::int64_t blk = 0; blk < blocks; ++blk) {
    in.integer("entity dimension");
    const int entity = in.integer("entity tag");
    const int type = in.integer("element type");
    const int nn = gmsh_nodes_per_element(type, tok);
    const auto n = in.count("elements in block", static_cast<std::size_t>(sb) * (1 + nn));
    const auto phys_it = volume_physical.find(entity);
    const int phys = phys_it == volume_physical.end() ? 0 : phys_it->second;
    ids.resize(static_cast<std::size_t>(nn));
    for (std::int64_t i = 0; i < n; ++i) {
      in.size("element tag");
      for (auto& id : ids) id = in.size("node tag");
      if (type == kGmshTet4) b.add_tet(ids, phys, tok);
    }
  }
  tok.expect("$EndElements");
}

TetMesh read_v4(Values& in, const std::string& source) {
  TextTokens& tok = in.tokens();
  Builder b;
  std::map<int, int> volume_physical;
  bool have_nodes = false;
  while (!tok.at_end()) {
    const std::string section = tok.next("a section name");
    if (section == "$Entities") {
      volume_physical = read_entities_v4(in);
    } else if (section == "$Nodes") {
      read_nodes_v4(in, b);
      have_nodes = true;
    } else if (section == "$Elements") {
      if (!have_nodes) tok.fail("$Nodes before $Elements", section);
      read_elements_v4(in, b, volume_physical);
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
  const auto data_size = tok.next_int("data size");
  const bool v2 = version.rfind("2.", 0) == 0;
  if (!v2 && version != "4.1") tok.fail("format version 1.0, 2.2 or 4.1", version);
  if (file_type != 0 && file_type != 1) tok.fail("file type 0 (ASCII) or 1 (binary)", std::to_string(file_type));
  const bool binary = file_type == 1;
  // Binary files: 2.x stores doubles (data size 8); 4.1 gives the writer's sizeof(size_t).
  if (binary && (v2 ? data_size != 8 : data_size != 4 && data_size != 8))
    tok.fail(v2 ? "data size 8" : "data size 4 or 8", std::to_string(data_size));
  if (binary) {
    // The int 1, written in the writer's byte order.
    tok.begin_binary();
    std::int32_t one = 0;
    tok.read_bytes(&one, sizeof one, "the binary int 1");
    if (one != 1) tok.fail("a binary mesh in this machine's byte order (the int 1 after the format line)", std::to_string(one));
  }
  tok.expect("$EndMeshFormat");
  Values in(tok, binary, static_cast<int>(data_size));
  return v2 ? read_v2(in, source) : read_v4(in, source);
}

}  // namespace softsim::mesh
