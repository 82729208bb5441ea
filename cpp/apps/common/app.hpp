#pragma once
// The command-line contract shared by every executable:
//   TOOL [MODE] --config FILE --out FILE [--flag ...]   run
//   TOOL --help | --version
// Exit codes: 0 success, 2 bad input (one line naming file, JSON pointer, expectation),
// 3 numerical failure (no artifact written), 1 internal error (out of memory included, in an
// OpenMP region too: one line, the run's files removed). A tool may finish with another code
// and its artifact written (AppContext::exit_code: haptic_sim serve's 4 and 5).
// SIGPIPE and SIGXFSZ are ignored: a write to a reader that left, or past the file-size limit,
// fails with an error the tool reports instead of killing it.
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "softsim/io/artifact.hpp"
#include "softsim/io/json_reader.hpp"

namespace softsim::app {

struct AppInfo {
  std::string name;
  std::string summary;              // one line for --help
  std::string config_help;          // what the config holds (for --help)
  std::vector<std::string> modes;   // optional positional modes (first one is the default)
  std::set<std::string> flags;      // extra boolean flags accepted, e.g. "--bench", "--force"
  bool needs_config = true;
  bool needs_out = true;
};

class AppContext {
 public:
  std::string mode;
  std::string config_path;
  std::string out_path;
  std::set<std::string> flags;
  nlohmann::json config_json;
  io::Provenance provenance;

  // The strict reader over the config root. A tool reads every key it understands and then
  // calls config().reject_unknown() before computing anything.
  const io::JsonReader& config() const { return *config_; }
  bool flag(const std::string& f) const { return flags.count(f) > 0; }
  // Records an input file's sha256 in the provenance and returns the path.
  std::string input(const std::string& path);
  // Checks an output file other than --out, named by config member `pointer` (a VTU file),
  // before anything is computed: the rules of --out (a regular file or a new name, not the
  // config, not a file another member names, not --out itself). Returns `path` ("" passes).
  std::string output(const std::string& path, const std::string& pointer) const;
  // The rules of output() for a file written in place as the run goes, which may also be a
  // named pipe (haptic_sim's visual stream).
  std::string stream_output(const std::string& path, const std::string& pointer) const;
  // The exit code of a run that finished (its artifact written): 0 unless the tool says why not.
  int exit_code = 0;
  // Writes the artifact at --out with this run's provenance.
  void write(const std::string& schema, int version, nlohmann::json payload);

  std::unique_ptr<io::JsonReader> config_;
};

int run_app(int argc, char** argv, const AppInfo& info,
            const std::function<void(AppContext&)>& body);

}  // namespace softsim::app
