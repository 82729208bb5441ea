#include "softsim/io/git_commit.hpp"

#include <cstdio>
#include <cstdlib>

namespace softsim::io {

namespace {
std::string read_commit() {
  if (const char* env = std::getenv("SOFTSIM_GIT_COMMIT"); env && *env) return env;
  std::string out;
  if (FILE* pipe = ::popen("git rev-parse HEAD 2>/dev/null", "r")) {
    char buffer[128];
    while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
    ::pclose(pipe);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out.size() == 40 ? out : "unknown";
}
}  // namespace

const std::string& git_commit() {
  static const std::string commit = read_commit();
  return commit;
}

}  // namespace softsim::io
