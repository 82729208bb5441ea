#pragma once
// Bad input found while a run is set up (after its configuration was read), such as a solver
// whose step is above its stability limit. The library names the setting at fault in the
// model's terms; whoever read the configuration knows where that setting came from and reports
// it there (async_sim: the JSON pointer of its config member).
#include <string>

#include "softsim/io/errors.hpp"

namespace softsim::multirate {

struct SettingAtFault {
  enum class Kind {
    kWholeSolver,      // the solver of the whole model
    kPrimarySolver,    // the solver of the primary region
    kSecondarySolver,  // the solver of secondary region `secondary_index`
    kProbeStiffness,   // the haptic loop's probe stiffness
  };
  Kind kind = Kind::kWholeSolver;
  int secondary_index = 0;  // 0-based, in the order the secondary regions were given
};

struct SetupError : InputError {
  SetupError(SettingAtFault setting_, const std::string& what) : InputError(what), setting(setting_) {}
  SettingAtFault setting;
};

}  // namespace softsim::multirate
