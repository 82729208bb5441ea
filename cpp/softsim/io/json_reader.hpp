#pragma once
// Strict reading of JSON configs and artifacts.
//
// Every value is read through a JsonReader that knows the file it came from and its JSON
// pointer, so any complaint is one line: "<file>: <pointer>: expected <what>, got <what>".
// An object reader remembers which keys were read; reject_unknown() then refuses the rest,
// so a typo in a config is an error rather than a silently ignored setting.
#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "softsim/io/errors.hpp"

namespace softsim::io {

class JsonReader {
 public:
  JsonReader(const nlohmann::json& value, std::string file, std::string pointer = "");

  // Parses a whole file; a missing file, one that is not a regular file or is too large
  // (io/limits.hpp), a syntax error, a key given twice in one object and nesting deeper than
  // kMaxJsonDepth are InputErrors naming the file (and the JSON pointer where there is one).
  static nlohmann::json parse_file(const std::string& path);
  // The same checks on text already read; `path` names it in messages.
  static nlohmann::json parse_text(const std::string& text, const std::string& path);

  const nlohmann::json& raw() const { return *value_; }
  const std::string& file() const { return file_; }
  std::string pointer() const { return pointer_.empty() ? "/" : pointer_; }

  // ---- object access (each read marks the key as known) ----
  bool has(const std::string& key) const;
  JsonReader at(const std::string& key) const;  // required member
  std::optional<JsonReader> optional(const std::string& key) const;
  // Marks keys as known without reading them (a caller that forwards them elsewhere).
  void accept(const std::string& key) const;
  // Refuses every member that was not read ("unknown field"), and a value that is not an
  // object at all (all of whose optional members would otherwise read as absent).
  void reject_unknown() const;
  std::vector<std::string> keys() const;

  // ---- array access ----
  std::size_t size() const;  // requires an array
  JsonReader operator[](std::size_t i) const;

  // ---- scalars at this node ----
  double as_double() const;  // finite number
  std::int64_t as_int() const;
  int as_int32() const;  // an integer that fits an `int` (checked before any narrowing)
  bool as_bool() const;
  std::string as_string() const;

  // ---- typed member shortcuts ----
  double get_double(const std::string& key) const { return at(key).as_double(); }
  double get_double(const std::string& key, double fallback) const;
  double get_positive(const std::string& key) const;
  double get_positive(const std::string& key, double fallback) const;
  std::int64_t get_int(const std::string& key) const { return at(key).as_int(); }
  std::int64_t get_int(const std::string& key, std::int64_t fallback) const;
  // An integer that must fit an `int` (counts, intervals): checked before any narrowing, so
  // 4294967297 is refused instead of silently becoming 1.
  int get_int32(const std::string& key) const;
  int get_int32(const std::string& key, int fallback) const;
  bool get_bool(const std::string& key, bool fallback) const;
  std::string get_string(const std::string& key) const { return at(key).as_string(); }
  std::string get_string(const std::string& key, const std::string& fallback) const;
  // One of a fixed set of strings.
  std::string get_choice(const std::string& key, const std::vector<std::string>& choices) const;
  std::string get_choice(const std::string& key, const std::vector<std::string>& choices,
                         const std::string& fallback) const;
  std::vector<double> get_doubles(const std::string& key) const;
  std::vector<double> get_doubles(const std::string& key, std::size_t expected_size) const;
  std::vector<std::int64_t> get_ints(const std::string& key) const;
  // The path of an input file named by string member `key`: an absolute path as it is; a
  // relative one against the folder of the file this reader came from (as most tools read
  // their configs), or, where no such file is there, against the working directory (configs
  // written before paths were resolved this way, and configs written into a scratch folder
  // with paths relative to where the tool runs). No file in either place: an InputError naming
  // the member and both folders.
  std::string get_input_path(const std::string& key) const;

  // Range check of a value already read from member `key`.
  void require(bool ok, const std::string& key, const std::string& expected) const;

  [[noreturn]] void fail(const std::string& expected) const;
  [[noreturn]] void fail_member(const std::string& key, const std::string& expected) const;

 private:
  std::string child_pointer(const std::string& key) const;
  std::string describe() const;

  const nlohmann::json* value_;
  std::string file_;
  std::string pointer_;
  std::shared_ptr<std::set<std::string>> read_keys_;
};

// A short description of a JSON value's type for error messages ("string \"abc\"", "null", ...).
std::string describe_json(const nlohmann::json& value);

}  // namespace softsim::io
