#include "config_source.hpp"

#include "json_convert.hpp"

namespace py = pybind11;

namespace softsim::python {

Config Config::from_python(const py::handle& value) {
  Config c;
  if (py::isinstance<py::dict>(value)) {
    c.source_ = kDictSource;
    c.json_ = std::make_unique<nlohmann::json>(to_json(value, c.source_));
    return c;
  }
  if (!py::isinstance<py::str>(value) && !py::hasattr(value, "__fspath__"))
    throw InputError("config: expected a dict or the path of a JSON file, got " +
                     py::str(py::type::of(value).attr("__name__")).cast<std::string>());
  c.source_ = py::str(py::module_::import("os").attr("fspath")(value)).cast<std::string>();
  {
    py::gil_scoped_release release;
    c.json_ = std::make_unique<nlohmann::json>(io::JsonReader::parse_file(c.source_));
  }
  if (!c.json_->is_object()) c.reader().fail("a JSON object");
  return c;
}

Config Config::from_json(nlohmann::json value, std::string source) {
  Config c;
  c.json_ = std::make_unique<nlohmann::json>(std::move(value));
  c.source_ = std::move(source);
  return c;
}

}  // namespace softsim::python
