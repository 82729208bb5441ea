#pragma once
// NumPy arrays the bindings return by copy.
#include <cstring>

#include <pybind11/numpy.h>

namespace softsim::python {

// `rows` rows of three doubles copied from `data` into a new rows x 3 array.
inline pybind11::array_t<double> rows3(const double* data, std::size_t rows) {
  pybind11::array_t<double> a({static_cast<pybind11::ssize_t>(rows), pybind11::ssize_t{3}});
  if (rows > 0) std::memcpy(a.mutable_data(), data, rows * 3 * sizeof(double));
  return a;
}

}  // namespace softsim::python
