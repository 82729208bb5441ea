#include "softsim/io/git_commit.hpp"

#include <cstdio>
#include <cstdlib>

// The source tree's path is compiled into this file alone (CMakeLists.txt), and the commit is
// asked for at run time: a binary that changed with every commit would invalidate the
// pipeline's cache, whose keys hash the binaries.
#ifndef SOFTSIM_GIT_SOURCE_DIR
#error "SOFTSIM_GIT_SOURCE_DIR (the softsim source tree) must be defined when compiling git_commit.cpp"
#endif

namespace softsim::io {

namespace {

// One argument for sh, whatever the path holds.
std::string shell_quoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

std::string describe_commit(const std::string& source_dir) {
  const std::string command = "git -C " + shell_quoted(source_dir) + " describe --always --dirty 2>/dev/null";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return "unknown";
  std::string out;
  char buffer[128];
  while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
  const int status = ::pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  // sh exits 127 when git is missing; git itself fails for a path that is no repository.
  if (status != 0 || out.empty() || out.find('\n') != std::string::npos) return "unknown";
  return out;
}

const std::string& git_commit() {
  static const std::string commit = [] {
    if (const char* env = std::getenv("SOFTSIM_GIT_COMMIT"); env && *env) return std::string(env);
    return describe_commit(SOFTSIM_GIT_SOURCE_DIR);
  }();
  return commit;
}

}  // namespace softsim::io
