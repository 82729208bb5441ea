#pragma once
// The three kinds of failure every executable distinguishes (ARCHITECTURE: Errors).
//   InputError     -> exit 2: bad file, bad JSON, value out of range; message names file and JSON pointer.
//   NumericalError -> exit 3: NaN, blow-up, inverted element, singular system, fit that did not converge.
//   anything else  -> exit 1: an internal bug.
#include <stdexcept>
#include <string>

namespace softsim {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct NumericalError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace softsim
