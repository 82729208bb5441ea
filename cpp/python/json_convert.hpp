#pragma once
// Python values <-> JSON, so that a config dict reaches the strict readers exactly as the
// executables' JSON files do, and a payload comes back as json.load would read the artifact's.
#include <string>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

namespace softsim::python {

// dict (str keys), list, tuple, str, int, float, bool, None, os.PathLike (its path) and NumPy
// arrays and scalars (their tolist()). Anything else is an InputError naming `source` and the
// JSON pointer of the value.
nlohmann::json to_json(const pybind11::handle& value, const std::string& source);

// JSON -> dict, list, str, int, float, bool, None.
pybind11::object from_json(const nlohmann::json& value);

}  // namespace softsim::python
