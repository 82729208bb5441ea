#pragma once
// The commit of the source tree the library was built from, for provenance:
// SOFTSIM_GIT_COMMIT if set, else `git describe --always --dirty` run in that source tree
// (an abbreviated hash, with "-dirty" when the tree had uncommitted changes), else "unknown"
// (the source tree is gone, e.g. an installed binary on another machine, or git is missing).
// Read at run time, once per process, and independent of the current directory.
#include <string>

namespace softsim::io {

const std::string& git_commit();

// `git describe --always --dirty` of the tree at `source_dir`, or "unknown" when git fails
// there (no such directory, not a repository, git missing).
std::string describe_commit(const std::string& source_dir);

}  // namespace softsim::io
