#include "softsim/io/json_reader.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <set>

#include "softsim/io/atomic_file.hpp"
#include "softsim/io/limits.hpp"

namespace softsim::io {

namespace {
// RFC 6901 escaping, plus control characters written as \u00XX: a key holding a NUL or a
// newline would otherwise cut the one-line error message short or split it.
std::string escape_pointer_token(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char code[8];
      std::snprintf(code, sizeof code, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += code;
    } else out += c;
  }
  return out;
}
// Refuses a key repeated in one object while the document is parsed: the parser would keep the
// last value only, so the first setting would be silently ignored. Refuses nesting deeper than
// kMaxJsonDepth before the deeper level is built: every later walk of the document (copying
// it into the provenance, flattening, destroying) recurses once per level, and a document
// nested tens of thousands deep would overflow the stack. Tracks the JSON pointer of the value
// being parsed (object keys, and array indices counted as elements end).
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(std::string file) : file_(std::move(file)) {}

  bool operator()(int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        if (open_.size() >= kMaxJsonDepth)
          throw InputError(file_ + ": " + pointer() + ": expected arrays and objects nested at most " +
                           std::to_string(kMaxJsonDepth) + " deep, got deeper");
        open_.push_back({event == Event::object_start, {}, "", 0});
        break;
      case Event::key: {
        Level& object = open_.back();
        object.key = parsed.get<std::string>();
        if (!object.keys.insert(object.key).second)
          throw InputError(file_ + ": " + pointer() + ": expected each key once in an object, got it twice");
        break;
      }
      case Event::object_end:
      case Event::array_end:
        open_.pop_back();
        element_done();
        break;
      case Event::value: element_done(); break;
    }
    return true;
  }

 private:
  struct Level {
    bool object;
    std::set<std::string> keys;  // object: the keys seen so far
    std::string key;             // object: the key of the member being parsed
    std::size_t index;           // array: the elements done so far
  };

  void element_done() {
    if (!open_.empty() && !open_.back().object) ++open_.back().index;
  }

  std::string pointer() const {
    std::string out;
    for (const Level& l : open_) out += "/" + (l.object ? escape_pointer_token(l.key) : std::to_string(l.index));
    return out;
  }

  std::string file_;
  std::vector<Level> open_;
};

}  // namespace

std::string describe_json(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::boolean: return value.get<bool>() ? "true" : "false";
    case nlohmann::json::value_t::string: {
      std::string s = value.get<std::string>();
      if (s.size() > 40) s = s.substr(0, 37) + "...";
      return "string \"" + s + "\"";
    }
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
    case nlohmann::json::value_t::number_float: return "number " + value.dump();
    case nlohmann::json::value_t::array: return "array of " + std::to_string(value.size());
    case nlohmann::json::value_t::object: return "object";
    default: return "unsupported value";
  }
}

JsonReader::JsonReader(const nlohmann::json& value, std::string file, std::string pointer)
    : value_(&value),
      file_(std::move(file)),
      pointer_(std::move(pointer)),
      read_keys_(std::make_shared<std::set<std::string>>()) {}

nlohmann::json JsonReader::parse_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": expected a JSON file, got a directory");
  return parse_text(read_text_file(path), path);
}

nlohmann::json JsonReader::parse_text(const std::string& text, const std::string& path) {
  if (text.empty()) throw InputError(path + ": expected a JSON document, got an empty file");
  try {
    // Comments are not JSON; NaN/Infinity literals are rejected by the parser itself.
    return nlohmann::json::parse(text, DuplicateKeyCheck(path));
  } catch (const nlohmann::json::exception& e) {  // syntax errors and out-of-range numbers
    std::string msg = e.what();
    // nlohmann's message starts with "[json.exception.parse_error.101] "; keep the useful part.
    const auto pos = msg.find("] ");
    if (pos != std::string::npos) msg = msg.substr(pos + 2);
    throw InputError(path + ": invalid JSON: " + msg);
  }
}

std::string JsonReader::child_pointer(const std::string& key) const {
  return pointer_ + "/" + escape_pointer_token(key);
}

std::string JsonReader::describe() const { return describe_json(*value_); }

std::string JsonReader::get_input_path(const std::string& key) const {
  namespace fs = std::filesystem;
  const std::string given = get_string(key);
  if (given.empty()) at(key).fail("a file path");
  const fs::path p(given);
  if (p.is_absolute()) {
    if (!fs::exists(p)) at(key).fail("an existing file (no file at that absolute path)");
    return given;
  }
  const fs::path folder = fs::path(file_).parent_path();
  if (!folder.empty()) {
    const fs::path beside = folder / p;
    if (fs::exists(beside)) return beside.lexically_normal().string();
  }
  if (fs::exists(p)) return given;
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  at(key).fail("a file path relative to the config's folder \"" + (folder.empty() ? std::string(".") : folder.string()) +
               "\" (or to the working directory \"" + (ec ? std::string(".") : cwd.string()) + "\"), but \"" + given +
               "\" is in neither");
}

void JsonReader::fail(const std::string& expected) const {
  throw InputError(file_ + ": " + pointer() + ": expected " + expected + ", got " + describe());
}

void JsonReader::fail_member(const std::string& key, const std::string& expected) const {
  if (has(key)) at(key).fail(expected);
  throw InputError(file_ + ": " + child_pointer(key) + ": expected " + expected + ", got nothing");
}

bool JsonReader::has(const std::string& key) const {
  return value_->is_object() && value_->contains(key);
}

JsonReader JsonReader::at(const std::string& key) const {
  if (!value_->is_object()) fail("an object");
  auto it = value_->find(key);
  if (it == value_->end())
    throw InputError(file_ + ": " + child_pointer(key) + ": missing required field");
  read_keys_->insert(key);
  return JsonReader(*it, file_, child_pointer(key));
}

std::optional<JsonReader> JsonReader::optional(const std::string& key) const {
  if (!value_->is_object()) fail("an object");
  if (!value_->contains(key)) return std::nullopt;
  return at(key);
}

void JsonReader::accept(const std::string& key) const { read_keys_->insert(key); }

void JsonReader::reject_unknown() const {
  // Every object reader ends here: a value of another type (whose optional members would all
  // read as absent) is refused rather than taken for an empty object.
  if (!value_->is_object()) fail("an object");
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    if (!read_keys_->count(it.key()))
      throw InputError(file_ + ": " + child_pointer(it.key()) + ": unknown field");
  }
}

std::vector<std::string> JsonReader::keys() const {
  if (!value_->is_object()) fail("an object");
  std::vector<std::string> out;
  for (auto it = value_->begin(); it != value_->end(); ++it) out.push_back(it.key());
  return out;
}

std::size_t JsonReader::size() const {
  if (!value_->is_array()) fail("an array");
  return value_->size();
}

JsonReader JsonReader::operator[](std::size_t i) const {
  if (!value_->is_array()) fail("an array");
  if (i >= value_->size()) fail("an array with more than " + std::to_string(i) + " elements");
  return JsonReader((*value_)[i], file_, pointer_ + "/" + std::to_string(i));
}

double JsonReader::as_double() const {
  if (!value_->is_number()) fail("a number");
  const double v = value_->get<double>();
  if (!std::isfinite(v)) fail("a finite number");
  return v;
}

std::int64_t JsonReader::as_int() const {
  // An unsigned value above INT64_MAX would wrap to a negative one.
  if (value_->is_number_unsigned() &&
      value_->get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    fail("an integer within the 64-bit range");
  if (value_->is_number_integer()) return value_->get<std::int64_t>();
  if (value_->is_number_float()) {
    const double v = value_->get<double>();
    if (std::isfinite(v) && std::floor(v) == v && std::fabs(v) < 9e15)
      return static_cast<std::int64_t>(v);
  }
  fail("an integer");
}

bool JsonReader::as_bool() const {
  if (!value_->is_boolean()) fail("true or false");
  return value_->get<bool>();
}

std::string JsonReader::as_string() const {
  if (!value_->is_string()) fail("a string");
  return value_->get<std::string>();
}

double JsonReader::get_double(const std::string& key, double fallback) const {
  return has(key) ? at(key).as_double() : fallback;
}

double JsonReader::get_positive(const std::string& key) const {
  const double v = get_double(key);
  if (!(v > 0)) at(key).fail("a positive number");
  return v;
}

double JsonReader::get_positive(const std::string& key, double fallback) const {
  return has(key) ? get_positive(key) : fallback;
}

std::int64_t JsonReader::get_int(const std::string& key, std::int64_t fallback) const {
  return has(key) ? at(key).as_int() : fallback;
}

int JsonReader::as_int32() const {
  const std::int64_t v = as_int();
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    fail("an integer within the 32-bit range");
  return static_cast<int>(v);
}

int JsonReader::get_int32(const std::string& key) const { return at(key).as_int32(); }

int JsonReader::get_int32(const std::string& key, int fallback) const {
  return has(key) ? get_int32(key) : fallback;
}

bool JsonReader::get_bool(const std::string& key, bool fallback) const {
  return has(key) ? at(key).as_bool() : fallback;
}

std::string JsonReader::get_string(const std::string& key, const std::string& fallback) const {
  return has(key) ? at(key).as_string() : fallback;
}

std::string JsonReader::get_choice(const std::string& key,
                                   const std::vector<std::string>& choices) const {
  const JsonReader node = at(key);
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + ("\"" + c + "\"");
  if (!node.raw().is_string()) node.fail("one of " + list);
  const std::string v = node.as_string();
  for (const auto& c : choices)
    if (c == v) return v;
  node.fail("one of " + list);
}

std::string JsonReader::get_choice(const std::string& key, const std::vector<std::string>& choices,
                                   const std::string& fallback) const {
  return has(key) ? get_choice(key, choices) : fallback;
}

std::vector<double> JsonReader::get_doubles(const std::string& key) const {
  const JsonReader node = at(key);
  std::vector<double> out(node.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = node[i].as_double();
  return out;
}

std::vector<double> JsonReader::get_doubles(const std::string& key, std::size_t expected) const {
  const JsonReader node = at(key);
  if (!node.raw().is_array() || node.raw().size() != expected)
    node.fail("an array of " + std::to_string(expected) + " numbers");
  return get_doubles(key);
}

std::vector<std::int64_t> JsonReader::get_ints(const std::string& key) const {
  const JsonReader node = at(key);
  std::vector<std::int64_t> out(node.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = node[i].as_int();
  return out;
}

void JsonReader::require(bool ok, const std::string& key, const std::string& expected) const {
  if (!ok) fail_member(key, expected);
}

}  // namespace softsim::io
