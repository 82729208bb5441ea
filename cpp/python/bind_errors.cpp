// The library's two failure kinds as Python exceptions, with the executables' messages
// (file or "<dict>", JSON pointer, what was expected). Other C++ exceptions are internal errors
// and reach Python as RuntimeError.
#include "bindings.hpp"
#include "softsim/io/errors.hpp"

namespace py = pybind11;

namespace softsim::python {

void bind_errors(py::module_& m) {
  auto input = py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  input.doc() =
      "Bad input: a malformed file or config, a value out of range (the executables' exit 2).\n"
      "The message names the file (or \"<dict>\" for a config passed as a dict), the JSON pointer\n"
      "and what was expected.";
  auto numerical = py::register_exception<NumericalError>(m, "NumericalError", PyExc_ArithmeticError);
  numerical.doc() =
      "A numerical failure: NaN, energy blow-up, inverted element, singular system, Newton or a\n"
      "fit not converged (the executables' exit 3).";
}

}  // namespace softsim::python
