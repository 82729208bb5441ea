#include "softsim/mesh/vtu_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <type_traits>
#include <utility>

#include "softsim/io/base64.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/mesh/vtk_cells.hpp"

namespace softsim::mesh {

namespace {

struct Tag {
  std::string name;
  std::map<std::string, std::string> attributes;
  bool closing = false;  // </name>
  bool empty = false;    // <name ... />
  std::size_t begin = 0, end = 0;  // the '<' and one past the '>'

  std::string get(const std::string& key, const std::string& fallback = "") const {
    const auto it = attributes.find(key);
    return it == attributes.end() ? fallback : it->second;
  }
};

// The element tags of the file's XML part, one after the other (no tree: a VTU is flat enough).
class TagScanner {
 public:
  TagScanner(const std::string& text, std::size_t end, const std::string& source)
      : text_(text), end_(end), source_(source) {}

  void seek(std::size_t pos) { pos_ = pos; }

  // The next element tag at or after the current position, skipping declarations, comments and
  // text; nullopt at the end.
  std::optional<Tag> next() {
    while (true) {
      const std::size_t lt = text_.find('<', pos_);
      if (lt == std::string::npos || lt >= end_) return std::nullopt;
      pos_ = lt;
      if (starts("<?")) {
        skip_past("?>");
      } else if (starts("<!--")) {
        skip_past("-->");
      } else if (starts("<!")) {
        skip_past(">");
      } else {
        return tag();
      }
    }
  }

  [[noreturn]] void fail(std::size_t at, const std::string& expected, const std::string& got) const {
    const std::string shown = got.size() > 40 ? got.substr(0, 37) + "..." : got;
    throw InputError(source_ + ": line " + std::to_string(line_of(at)) + ": expected " + expected + ", got " +
                     (got.empty() ? "end of file" : "\"" + shown + "\""));
  }

  int line_of(std::size_t at) const {
    return 1 + static_cast<int>(std::count(text_.begin(), text_.begin() + std::min(at, text_.size()), '\n'));
  }

 private:
  bool starts(const char* s) const { return text_.compare(pos_, std::strlen(s), s) == 0; }

  void skip_past(const char* close) {
    const std::size_t at = text_.find(close, pos_);
    if (at == std::string::npos || at >= end_) fail(pos_, std::string("\"") + close + "\"", "");
    pos_ = at + std::strlen(close);
  }

  void skip_space() {
    while (pos_ < end_ && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }

  static bool name_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':' || c == '-' || c == '.';
  }

  std::string name() {
    const std::size_t start = pos_;
    while (pos_ < end_ && name_char(text_[pos_])) ++pos_;
    if (pos_ == start) fail(start, "a name", text_.substr(start, std::min<std::size_t>(end_ - start, 20)));
    return text_.substr(start, pos_ - start);
  }

  static std::string unescape(const std::string& s) {
    static const std::pair<const char*, char> kEntities[] = {
        {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
      bool replaced = false;
      for (const auto& [entity, c] : kEntities)
        if (s.compare(i, std::strlen(entity), entity) == 0) {
          out += c;
          i += std::strlen(entity) - 1;
          replaced = true;
          break;
        }
      if (!replaced) out += s[i];
    }
    return out;
  }

  Tag tag() {
    Tag t;
    t.begin = pos_++;
    if (pos_ < end_ && text_[pos_] == '/') {
      t.closing = true;
      ++pos_;
    }
    t.name = name();
    while (true) {
      skip_space();
      if (pos_ >= end_) fail(t.begin, "the end of tag <" + t.name + ">", "");
      const char c = text_[pos_];
      if (c == '>') {
        ++pos_;
        break;
      }
      if (c == '/' && pos_ + 1 < end_ && text_[pos_ + 1] == '>') {
        t.empty = true;
        pos_ += 2;
        break;
      }
      const std::size_t at = pos_;
      const std::string key = name();
      skip_space();
      if (pos_ >= end_ || text_[pos_] != '=') fail(at, "=\"value\" after attribute " + key, text_.substr(pos_, 10));
      ++pos_;
      skip_space();
      const char quote = pos_ < end_ ? text_[pos_] : '\0';
      if (quote != '"' && quote != '\'') fail(at, "a quoted value of attribute " + key, text_.substr(pos_, 10));
      const std::size_t close = text_.find(quote, pos_ + 1);
      if (close == std::string::npos || close >= end_) fail(at, "the closing quote of attribute " + key, "");
      t.attributes[key] = unescape(text_.substr(pos_ + 1, close - pos_ - 1));
      pos_ = close + 1;
    }
    t.end = pos_;
    return t;
  }

  const std::string& text_;
  std::size_t end_;
  const std::string& source_;
  std::size_t pos_ = 0;
};

struct DataArray {
  Tag tag;
  std::string section;  // PointData, CellData, Points or Cells
  std::size_t content_begin = 0, content_end = 0;
  std::string name() const { return tag.get("Name"); }
};

// A value of the other byte order: values and headers are 1, 2, 4 or 8 bytes long.
void reverse_bytes(unsigned char* b, std::size_t n) {
  switch (n) {
    case 2: std::swap(b[0], b[1]); break;
    case 4: std::swap(b[0], b[3]); std::swap(b[1], b[2]); break;
    case 8: for (int i = 0; i < 4; ++i) std::swap(b[i], b[7 - i]); break;
    default: break;
  }
}

struct ScalarType {
  bool integral = false;
  bool is_signed = true;
  std::size_t size = 0;
};

std::optional<ScalarType> scalar_type(const std::string& name) {
  static const std::map<std::string, ScalarType> kTypes = {
      {"Int8", {true, true, 1}},    {"UInt8", {true, false, 1}},  {"Int16", {true, true, 2}},
      {"UInt16", {true, false, 2}}, {"Int32", {true, true, 4}},   {"UInt32", {true, false, 4}},
      {"Int64", {true, true, 8}},   {"UInt64", {true, false, 8}}, {"Float32", {false, true, 4}},
      {"Float64", {false, true, 8}}};
  const auto it = kTypes.find(name);
  if (it == kTypes.end()) return std::nullopt;
  return it->second;
}

// The file-wide settings every binary array is decoded with.
struct Layout {
  bool swap = false;              // file byte order differs from the machine's
  std::size_t header_size = 4;    // UInt32 or UInt64 byte count before each binary block
  std::size_t appended_begin = 0; // first byte after the '_' of <AppendedData>
  bool has_appended = false;
};

class Reader {
 public:
  Reader(const std::string& bytes, const TagScanner& xml, const Layout& layout)
      : bytes_(bytes), xml_(xml), layout_(layout) {}

  // The values of `a` as doubles (any numeric type) or 64-bit integers (integer types only).
  // `expected` values, or any number when negative.
  template <class T>
  std::vector<T> values(const DataArray& a, std::int64_t expected) const {
    const std::string type_name = a.tag.get("type");
    const auto type = scalar_type(type_name);
    if (!type) fail(a, "a numeric type (Int8 ... UInt64, Float32, Float64)", type_name);
    if (std::is_integral_v<T> && !type->integral) fail(a, "an integer type", type_name);
    const std::string format = a.tag.get("format");
    std::vector<T> out;
    if (format == "ascii") {
      const char* p = bytes_.data() + a.content_begin;
      const char* end = bytes_.data() + a.content_end;
      while (true) {
        while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
        if (p >= end) break;
        const char* q = p;
        while (q < end && !std::isspace(static_cast<unsigned char>(*q))) ++q;
        const std::string token(p, q);
        out.push_back(parse<T>(a, token, *type));
        p = q;
      }
    } else if (format == "binary") {
      const auto decoded =
          io::base64_decode(std::string_view(bytes_).substr(a.content_begin, a.content_end - a.content_begin));
      if (!decoded) fail(a, "base64 text (format=\"binary\")", "other characters");
      out = block<T>(a, *type, *decoded, 0);
    } else if (format == "appended") {
      if (!layout_.has_appended) fail(a, "an <AppendedData> section for format=\"appended\"", "none");
      const std::string offset = a.tag.get("offset");
      char* stop = nullptr;
      const unsigned long long at = std::strtoull(offset.c_str(), &stop, 10);
      if (offset.empty() || *stop != '\0' || offset[0] == '-') fail(a, "a byte offset", offset);
      if (at > bytes_.size() - layout_.appended_begin) fail(a, "an offset within the appended data", offset);
      out = block<T>(a, *type, bytes_, layout_.appended_begin + at);
    } else {
      fail(a, "format \"ascii\", \"binary\" or \"appended\"", format);
    }
    if (expected >= 0 && static_cast<std::int64_t>(out.size()) != expected)
      fail(a, std::to_string(expected) + " values", std::to_string(out.size()) + " values");
    return out;
  }

  [[noreturn]] void fail(const DataArray& a, const std::string& expected, const std::string& got) const {
    const std::string name = a.name().empty() ? a.section : a.name();
    xml_.fail(a.tag.begin, expected + " in DataArray \"" + name + "\"", got);
  }

 private:
  template <class T>
  T parse(const DataArray& a, const std::string& token, const ScalarType& type) const {
    char* end = nullptr;
    if constexpr (std::is_integral_v<T>) {
      errno = 0;
      const long long v = std::strtoll(token.c_str(), &end, 10);
      if (end == token.c_str() || *end != '\0' || errno == ERANGE) fail(a, "an integer", token);
      return v;
    } else {
      const double v = type.integral ? static_cast<double>(std::strtoll(token.c_str(), &end, 10))
                                     : std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(v)) fail(a, "a finite number", token);
      return v;
    }
  }

  // One binary block (byte count header, then the values) starting at `at` of `data`.
  template <class T>
  std::vector<T> block(const DataArray& a, const ScalarType& type, const std::string& data, std::size_t at) const {
    const std::size_t hs = layout_.header_size;
    if (data.size() < at || data.size() - at < hs) fail(a, "a byte-count header", "end of data");
    unsigned char raw[8];
    std::memcpy(raw, data.data() + at, hs);
    if (layout_.swap) reverse_bytes(raw, hs);
    std::uint64_t count = 0;
    if (hs == 4) {
      std::uint32_t c32;
      std::memcpy(&c32, raw, 4);
      count = c32;
    } else {
      std::memcpy(&count, raw, 8);
    }
    if (count > data.size() - at - hs)
      fail(a, std::to_string(count) + " bytes of data after the header", std::to_string(data.size() - at - hs));
    if (count % type.size != 0) fail(a, "a byte count that is a multiple of the value size", std::to_string(count));
    std::vector<T> out(count / type.size);
    const char* p = data.data() + at + hs;
    for (std::size_t i = 0; i < out.size(); ++i, p += type.size) out[i] = convert<T>(a, type, p);
    return out;
  }

  template <class T>
  T convert(const DataArray& a, const ScalarType& type, const char* p) const {
    unsigned char b[8];
    std::memcpy(b, p, type.size);
    if (layout_.swap) reverse_bytes(b, type.size);
    if (!type.integral) {
      double v;
      if (type.size == 4) {
        float f;
        std::memcpy(&f, b, 4);
        v = f;
      } else {
        std::memcpy(&v, b, 8);
      }
      if (!std::isfinite(v)) fail(a, "finite values", std::to_string(v));
      return static_cast<T>(v);
    }
    std::int64_t v = 0;
    switch (type.size) {
      case 1: v = type.is_signed ? std::int64_t(std::int8_t(b[0])) : std::int64_t(b[0]); break;
      case 2: {
        std::uint16_t u;
        std::memcpy(&u, b, 2);
        v = type.is_signed ? std::int64_t(std::int16_t(u)) : std::int64_t(u);
        break;
      }
      case 4: {
        std::uint32_t u;
        std::memcpy(&u, b, 4);
        v = type.is_signed ? std::int64_t(std::int32_t(u)) : std::int64_t(u);
        break;
      }
      default: {
        std::uint64_t u;
        std::memcpy(&u, b, 8);
        if (!type.is_signed && u > static_cast<std::uint64_t>(INT64_MAX)) fail(a, "values below 2^63", std::to_string(u));
        v = static_cast<std::int64_t>(u);
      }
    }
    return static_cast<T>(v);
  }

  const std::string& bytes_;
  const TagScanner& xml_;
  const Layout& layout_;
};

std::int64_t count_attribute(const Tag& tag, const std::string& key, const TagScanner& xml) {
  const std::string v = tag.get(key);
  char* end = nullptr;
  errno = 0;
  const long long n = std::strtoll(v.c_str(), &end, 10);
  if (v.empty() || *end != '\0' || n < 0 || errno == ERANGE || n > INT_MAX)
    xml.fail(tag.begin, key + "=\"a count\" on <" + tag.name + ">", v);
  return n;
}

}  // namespace

TetMesh read_vtu(const std::string& bytes, const std::string& source) {
  // Raw appended data may hold any byte, '<' included: the XML part ends where it begins.
  const std::size_t appended = bytes.find("<AppendedData");
  const std::size_t xml_end = appended == std::string::npos ? bytes.size() : appended;
  TagScanner xml(bytes, xml_end, source);

  const auto root = xml.next();
  if (!root || root->name != "VTKFile") xml.fail(0, "a VTK XML file (<VTKFile ...>)", root ? root->name : "");
  if (root->get("type") != "UnstructuredGrid")
    xml.fail(root->begin, "type=\"UnstructuredGrid\" on <VTKFile>", root->get("type"));
  if (!root->get("compressor").empty())
    xml.fail(root->begin, "an uncompressed file (no compressor; save it from ParaView with compression None)",
             root->get("compressor"));
  Layout layout;
  const std::string byte_order = root->get("byte_order", "LittleEndian");
  if (byte_order != "LittleEndian" && byte_order != "BigEndian")
    xml.fail(root->begin, "byte_order \"LittleEndian\" or \"BigEndian\"", byte_order);
  const bool little = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;
  layout.swap = (byte_order == "LittleEndian") != little;
  const std::string header_type = root->get("header_type", "UInt32");
  if (header_type != "UInt32" && header_type != "UInt64")
    xml.fail(root->begin, "header_type \"UInt32\" or \"UInt64\"", header_type);
  layout.header_size = header_type == "UInt64" ? 8 : 4;

  std::int64_t num_points = -1, num_cells = -1;
  std::string section;
  std::vector<DataArray> arrays;
  while (const auto tag = xml.next()) {
    if (tag->name == "Piece" && !tag->closing) {
      if (num_points >= 0) xml.fail(tag->begin, "a single <Piece>", "a second one");
      num_points = count_attribute(*tag, "NumberOfPoints", xml);
      num_cells = count_attribute(*tag, "NumberOfCells", xml);
    } else if (tag->name == "PointData" || tag->name == "CellData" || tag->name == "Points" || tag->name == "Cells") {
      section = tag->closing || tag->empty ? "" : tag->name;
    } else if (tag->name == "DataArray" && !tag->closing) {
      DataArray a;
      a.tag = *tag;
      a.section = section;
      a.content_begin = a.content_end = tag->end;
      if (!tag->empty) a.content_end = std::min(bytes.find('<', tag->end), xml_end);
      if (!section.empty()) arrays.push_back(std::move(a));
    }
  }
  if (num_points < 0) xml.fail(bytes.size(), "a <Piece NumberOfPoints=... NumberOfCells=...>", "");

  if (appended != std::string::npos) {
    TagScanner tail(bytes, bytes.size(), source);
    tail.seek(appended);
    const Tag tag = *tail.next();
    if (tag.get("encoding") != "raw")
      xml.fail(appended, "<AppendedData encoding=\"raw\"> (base64 appended data is not supported)", tag.get("encoding"));
    const std::size_t underscore = bytes.find('_', tag.end);
    if (underscore == std::string::npos) xml.fail(appended, "'_' before the appended data", "");
    layout.has_appended = true;
    layout.appended_begin = underscore + 1;
  }

  const Reader reader(bytes, xml, layout);
  const DataArray* points = nullptr;
  std::map<std::string, const DataArray*> cell_arrays;
  for (const DataArray& a : arrays) {
    if (a.section == "Points") points = &a;
    if (a.section == "Cells") cell_arrays[a.name()] = &a;
  }
  if (!points) xml.fail(bytes.size(), "a <Points> DataArray", "");
  if (points->tag.get("NumberOfComponents", "1") != "3")
    reader.fail(*points, "NumberOfComponents=\"3\"", points->tag.get("NumberOfComponents", "1"));
  const std::vector<double> xyz = reader.values<double>(*points, 3 * num_points);
  std::vector<Eigen::Vector3d> nodes(static_cast<std::size_t>(num_points));
  for (std::size_t i = 0; i < nodes.size(); ++i) nodes[i] = Eigen::Vector3d(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);

  for (const char* name : {"connectivity", "offsets", "types"})
    if (!cell_arrays.count(name)) xml.fail(bytes.size(), std::string("a <Cells> DataArray \"") + name + "\"", "");
  VtkCells cells;
  const std::vector<std::int64_t> ends = reader.values<std::int64_t>(*cell_arrays["offsets"], num_cells);
  cells.offsets.insert(cells.offsets.end(), ends.begin(), ends.end());
  cells.connectivity = reader.values<std::int64_t>(*cell_arrays["connectivity"], -1);
  for (std::int64_t t : reader.values<std::int64_t>(*cell_arrays["types"], num_cells))
    cells.types.push_back(static_cast<int>(std::clamp<std::int64_t>(t, -1, 255)));

  std::map<std::string, std::vector<int>> tags;
  for (const DataArray& a : arrays) {
    if (a.section != "CellData" || a.tag.get("NumberOfComponents", "1") != "1") continue;
    const auto type = scalar_type(a.tag.get("type"));
    if (!type || !type->integral) continue;
    std::vector<int>& tag = tags[a.name()];
    for (std::int64_t v : reader.values<std::int64_t>(a, num_cells)) {
      if (v < INT_MIN || v > INT_MAX) reader.fail(a, "tag values in the int range", std::to_string(v));
      tag.push_back(static_cast<int>(v));
    }
  }
  return tets_from_vtk_cells(std::move(nodes), cells, tags, source);
}

}  // namespace softsim::mesh
