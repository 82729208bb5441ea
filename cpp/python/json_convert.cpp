#include "json_convert.hpp"

#include "softsim/io/errors.hpp"

namespace py = pybind11;

namespace softsim::python {

namespace {

std::string pointer_token(const std::string& key) {  // RFC 6901 escaping, as in the readers' messages
  std::string out;
  for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}

nlohmann::json convert(const py::handle& v, const std::string& source, const std::string& pointer) {
  auto fail = [&](const std::string& expected) -> nlohmann::json {
    const std::string type = py::str(py::type::of(v).attr("__name__"));
    throw InputError(source + ": " + (pointer.empty() ? "/" : pointer) + ": expected " + expected + ", got " + type);
  };
  if (v.is_none()) return nullptr;
  // bool before int: Python's bool is an int.
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>();
  if (py::isinstance<py::int_>(v)) {
    try {
      return v.cast<std::int64_t>();
    } catch (const py::cast_error&) {
      try {
        return v.cast<std::uint64_t>();
      } catch (const py::cast_error&) {
        return fail("an integer within 64 bits");
      }
    }
  }
  if (py::isinstance<py::float_>(v)) return v.cast<double>();
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::isinstance<py::dict>(v)) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, item] : v.cast<py::dict>()) {
      if (!py::isinstance<py::str>(key)) fail("an object with string keys");
      const std::string k = key.cast<std::string>();
      out[k] = convert(item, source, pointer + "/" + pointer_token(k));
    }
    return out;
  }
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    nlohmann::json out = nlohmann::json::array();
    std::size_t i = 0;
    for (const auto& item : v) out.push_back(convert(item, source, pointer + "/" + std::to_string(i++)));
    return out;
  }
  if (py::hasattr(v, "__fspath__")) return convert(v.attr("__fspath__")(), source, pointer);
  // NumPy arrays and scalars become the Python lists and numbers they stand for.
  if (py::hasattr(v, "tolist") && py::hasattr(v, "dtype")) return convert(v.attr("tolist")(), source, pointer);
  return fail("a JSON value (dict, list, str, int, float, bool or None)");
}

}  // namespace

nlohmann::json to_json(const py::handle& value, const std::string& source) { return convert(value, source, ""); }

py::object from_json(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::null: return py::none();
    case nlohmann::json::value_t::boolean: return py::bool_(v.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(v.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(v.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: return py::float_(v.get<double>());
    case nlohmann::json::value_t::string: return py::str(v.get_ref<const std::string&>());
    case nlohmann::json::value_t::array: {
      py::list out(v.size());
      for (std::size_t i = 0; i < v.size(); ++i) out[i] = from_json(v[i]);
      return std::move(out);
    }
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (auto it = v.begin(); it != v.end(); ++it) out[py::str(it.key())] = from_json(it.value());
      return std::move(out);
    }
    default: throw std::logic_error("JSON value of no Python counterpart (binary)");
  }
}

}  // namespace softsim::python
