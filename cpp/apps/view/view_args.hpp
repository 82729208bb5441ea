#pragma once
// haptic_sim view's own command-line options, taken out of the arguments before the shared
// command-line contract (common/app.hpp) reads the rest:
//   --port N (0: a free one)  --host ADDR (127.0.0.1)  --web DIR  --record FILE
//   --frames N (0: until stopped)  --latency S (0.025)
#include <string>
#include <vector>

namespace softsim::view {

struct ViewArgs {
  bool view = false;  // the mode is "view"
  int port = 8080;
  std::string host = "127.0.0.1";
  std::string web_root;  // empty: the build tree's (SOFTSIM_VIEW_WEB_DIR)
  std::string record;    // the session's tip trajectory ("t x y z" lines), for `run` to replay
  long frames = 0;
  double latency = 0.025;
};

// Removes the view options from `args` (argv without the program name) when the mode is "view";
// InputError for a missing or bad value.
ViewArgs take_view_args(std::vector<std::string>& args);

}  // namespace softsim::view
