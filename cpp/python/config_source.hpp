#pragma once
// A tool's config as the Python API receives it: a dict, named "<dict>" in messages, or the path
// of a JSON file, named by its path and parsed exactly as the executables' --config. Computations
// run with the GIL released, and a ConfigInputError (a config member found at fault after
// reading, which knows its JSON pointer but not the file) gets the config's name in front, as
// the executables' one-line message has it.
#include <memory>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

#include "softsim/io/errors.hpp"
#include "softsim/io/json_reader.hpp"

namespace softsim::python {

inline constexpr const char* kDictSource = "<dict>";
// Stands for the config's "mesh" when a softsim.Mesh is passed instead (read_dhd_config reads the
// key; nothing loads it).
inline constexpr const char* kMeshObject = "<softsim.Mesh>";

class Config {
 public:
  // `value`: a dict, or a str / os.PathLike naming a JSON file. The root must be an object.
  static Config from_python(const pybind11::handle& value);
  // A config the API assembles itself (keyword arguments), named `source` in messages.
  static Config from_json(nlohmann::json value, std::string source);

  const std::string& source() const { return source_; }
  nlohmann::json& json() { return *json_; }
  const nlohmann::json& json() const { return *json_; }
  // A fresh strict reader over the root (each reader remembers the keys it has read).
  io::JsonReader reader() const { return io::JsonReader(*json_, source_); }

 private:
  std::unique_ptr<nlohmann::json> json_;  // readers point into it: a stable address
  std::string source_;
};

// Runs `f` with the GIL released, naming `source` in a ConfigInputError's message.
template <class F>
auto released(const std::string& source, F&& f) -> decltype(f()) {
  pybind11::gil_scoped_release release;
  try {
    return f();
  } catch (const ConfigInputError& e) {
    throw InputError(source + ": " + e.pointer + ": " + e.what());
  }
}

}  // namespace softsim::python
