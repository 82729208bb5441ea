// softsim._core: the compiled half of the Python package softsim (cpp/python/softsim/).
#include "bindings.hpp"
#include "softsim/version.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() = "softsim's C++ library bound with pybind11; import the package softsim, not this module.";
  m.attr("__version__") = softsim::kVersion;
  // Errors first: the other bindings' docstrings name them.
  softsim::python::bind_errors(m);
  softsim::python::bind_mesh(m);
  softsim::python::bind_solve(m);
  softsim::python::bind_rpim(m);
  softsim::python::bind_fit(m);
  softsim::python::bind_scene(m);
}
