#pragma once
// The commit of the working tree a tool runs in, for provenance: SOFTSIM_GIT_COMMIT if set,
// else `git rev-parse HEAD` in the current directory, else "unknown". Read once per process.
#include <string>

namespace softsim::io {

const std::string& git_commit();

}  // namespace softsim::io
