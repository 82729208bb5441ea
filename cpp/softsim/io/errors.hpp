#pragma once
// The three kinds of failure every executable distinguishes (ARCHITECTURE: Errors).
//   InputError     -> exit 2: bad file, bad JSON, value out of range; message names file and JSON pointer.
//   NumericalError -> exit 3: NaN, blow-up, inverted element, singular system, fit that did not converge.
//   anything else  -> exit 1: an internal bug.
#include <stdexcept>
#include <string>
#include <utility>

namespace softsim {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Bad input found after the config was read (e.g. a time step above the stability limit): the
// thrower (a solver, or a tool's config layer translating a library error) names the config
// member at fault but not the file; run_app prefixes the file.
struct ConfigInputError : InputError {
  ConfigInputError(std::string pointer_, const std::string& what)
      : InputError(what), pointer(std::move(pointer_)) {}
  std::string pointer;  // JSON pointer into the tool's config, e.g. "/solver/dt"
};

struct NumericalError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace softsim
