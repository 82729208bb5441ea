#pragma once
// The message of the InputError a call throws ("" when it throws none), for tests of what bad
// input is told.
#include <functional>
#include <string>

#include "softsim/io/errors.hpp"

namespace softsim::test_support {

inline std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace softsim::test_support
