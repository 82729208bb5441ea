#include "common/app.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>

#include "softsim/io/errors.hpp"
#include "softsim/io/git_commit.hpp"
#include "softsim/io/output_guard.hpp"
#include "softsim/io/sha256.hpp"
#include "softsim/version.hpp"

namespace softsim::app {

std::string AppContext::input(const std::string& path) {
  provenance.input_sha256[path] = io::sha256_file(path);
  io::guard_input(path);
  return path;
}

void AppContext::write(const std::string& schema, int version, nlohmann::json payload) {
  io::write_artifact(out_path, schema, version, provenance, std::move(payload));
}

namespace {

void print_help(const AppInfo& info) {
  std::cout << info.name << " " << kVersion << ": " << info.summary << "\n\nUsage:\n  " << info.name;
  if (!info.modes.empty()) {
    std::cout << " [";
    for (std::size_t i = 0; i < info.modes.size(); ++i) std::cout << (i ? "|" : "") << info.modes[i];
    std::cout << "]";
  }
  if (info.needs_config) std::cout << " --config FILE";
  if (info.needs_out) std::cout << " --out FILE";
  for (const auto& f : info.flags) std::cout << " [" << f << "]";
  std::cout << "\n  " << info.name << " --help | --version\n\n"
            << "Exit codes: 0 ok, 1 internal error, 2 bad input, 3 numerical failure.\n";
  if (!info.config_help.empty()) std::cout << "\nConfig:\n" << info.config_help << "\n";
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;  // a path that does not exist is no file at all
  return std::filesystem::equivalent(a, b, ec) && !ec;
}

// Whether two outputs, either of which may not exist yet, would be the same file.
bool same_output(const std::string& a, const std::string& b) {
  if (same_file(a, b)) return true;
  std::error_code ea, eb;
  const auto ca = std::filesystem::weakly_canonical(a, ea), cb = std::filesystem::weakly_canonical(b, eb);
  return !ea && !eb && ca == cb;
}

// Why `path`, an output of this run named by `label` (the command line's "--out PATH", or the
// config file and the member's JSON pointer), may not be written, or "": a directory or a special file (a device
// such as /dev/null would be replaced by a regular file), the config, or a file named by
// another string member of the config (an input: the failure would delete the user's file, and
// success overwrite it). `own` is the member naming the output itself.
std::string output_conflict(const AppContext& ctx, const std::string& path, const std::string& label,
                            const std::string& own, bool stream = false) {
  if (!ctx.config_path.empty() && same_file(ctx.config_path, path))
    return label + ": expected a file other than the --config file";
  try {
    if (stream)
      io::check_stream_path(path, label);
    else
      io::check_output_path(path, label);
  } catch (const InputError& e) {
    return e.what();
  }
  if (!ctx.config_json.is_object()) return "";
  const nlohmann::json members = ctx.config_json.flatten();  // keys are JSON pointers
  for (auto it = members.begin(); it != members.end(); ++it)
    if (it.key() != own && it->is_string() && same_file(it->get<std::string>(), path))
      return ctx.config_path + ": " + it.key() + ": expected a file other than the " +
             (own.empty() ? std::string("--out") : own) + " file " + path;
  return "";
}

std::string out_path_conflict(const AppContext& ctx) {
  return output_conflict(ctx, ctx.out_path, "command line: --out " + ctx.out_path, "");
}

// A failed run removes the files it put in place (VTU snapshots written before the failure, say)
// and nothing else: not an --out that was refused, not a device, not an input, and not an earlier
// run's artifact at --out, which this run never replaced (the artifact is written last, by one
// rename) and which stays as it was; the exit code, not the file's presence, says whether this
// run succeeded.
void remove_failed_output() { io::undo_written(); }

// The tool's name for the last-resort handler below.
const char* g_tool_name = "softsim";

// An exception that leaves an OpenMP region (or any noexcept frame) ends in std::terminate,
// not in run_app's handlers: out of memory there would be SIGABRT. This handler gives it the
// same end as everywhere else: one line, the run's files removed, exit 1.
[[noreturn]] void on_terminate() {
  // Every thread of a parallel region may get here: the first one speaks and ends the process.
  static std::atomic_flag taken = ATOMIC_FLAG_INIT;
  if (taken.test_and_set())
    for (;;) ::pause();
  const char* what = "an unknown failure";
  bool out_of_memory = false;
  if (const std::exception_ptr e = std::current_exception()) {
    try {
      std::rethrow_exception(e);
    } catch (const std::bad_alloc&) {
      out_of_memory = true;
    } catch (const std::exception& x) {
      what = x.what();
    } catch (...) {
    }
  }
  std::fprintf(stderr, "%s: internal error: %s\n", g_tool_name,
               out_of_memory ? "out of memory (the run's memory estimate passed the limit: lower "
                               "SOFTSIM_MEMORY_LIMIT_MB to what this machine can give)"
                             : what);
  remove_failed_output();
  std::_Exit(1);
}

}  // namespace

std::string AppContext::stream_output(const std::string& path, const std::string& pointer) const {
  if (path.empty()) return path;
  if (same_output(path, out_path))
    throw InputError(config_path + ": " + pointer + ": expected a file other than the --out file " + out_path);
  if (const std::string conflict = output_conflict(*this, path, config_path + ": " + pointer, pointer, true);
      !conflict.empty())
    throw InputError(conflict);
  return path;
}

std::string AppContext::output(const std::string& path, const std::string& pointer) const {
  if (path.empty()) return path;
  if (same_output(path, out_path))
    throw InputError(config_path + ": " + pointer + ": expected a file other than the --out file " + out_path);
  if (const std::string conflict = output_conflict(*this, path, config_path + ": " + pointer, pointer); !conflict.empty())
    throw InputError(conflict);
  return path;
}

int run_app(int argc, char** argv, const AppInfo& info,
            const std::function<void(AppContext&)>& body) {
  AppContext ctx;
  ctx.provenance.tool = info.name;
  io::reset_output_guard();
  g_tool_name = info.name.c_str();
  std::set_terminate(on_terminate);
  std::signal(SIGPIPE, SIG_IGN);
  std::signal(SIGXFSZ, SIG_IGN);
  try {
    std::vector<std::string> args(argv + 1, argv + argc);
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      if (a == "--help" || a == "-h") {
        print_help(info);
        return 0;
      } else if (a == "--version") {
        std::cout << info.name << " " << kVersion << " (" << io::git_commit() << ")\n";
        return 0;
      } else if (a == "--config" || a == "--out") {
        if (i + 1 >= args.size()) throw InputError("command line: " + a + " expects a file name");
        std::string& path = a == "--config" ? ctx.config_path : ctx.out_path;
        if (!path.empty()) throw InputError("command line: " + a + " given twice");
        path = args[++i];
      } else if (info.flags.count(a)) {
        ctx.flags.insert(a);
      } else if (!a.empty() && a[0] != '-' && ctx.mode.empty() && !info.modes.empty()) {
        bool known = false;
        for (const auto& m : info.modes) known = known || m == a;
        if (!known) throw InputError("command line: unknown mode \"" + a + "\" (see --help)");
        ctx.mode = a;
      } else {
        throw InputError("command line: unknown argument \"" + a + "\" (see --help)");
      }
    }
    if (ctx.mode.empty() && !info.modes.empty()) ctx.mode = info.modes.front();
    if (info.needs_config && ctx.config_path.empty()) throw InputError("command line: --config FILE is required");
    if (info.needs_out && ctx.out_path.empty()) throw InputError("command line: --out FILE is required");
    if (!ctx.config_path.empty()) {
      ctx.config_json = io::JsonReader::parse_file(ctx.config_path);
      io::guard_input(ctx.config_path);
      ctx.config_ = std::make_unique<io::JsonReader>(ctx.config_json, ctx.config_path);
      if (!ctx.config_json.is_object()) ctx.config_->fail("a JSON object");
      ctx.provenance.config = ctx.config_json;
    } else {
      static const nlohmann::json empty = nlohmann::json::object();
      ctx.config_ = std::make_unique<io::JsonReader>(empty, "<no config>");
    }
    if (!ctx.out_path.empty())
      if (const std::string conflict = out_path_conflict(ctx); !conflict.empty()) throw InputError(conflict);
    body(ctx);
    io::commit_written();
    return ctx.exit_code;
  } catch (const InputError& e) {
    std::cerr << info.name << ": error: ";
    // A config member found at fault after reading knows its JSON pointer but not the file.
    if (const auto* at = dynamic_cast<const ConfigInputError*>(&e))
      std::cerr << ctx.config_path << ": " << at->pointer << ": ";
    std::cerr << e.what() << "\n";
    remove_failed_output();
    return 2;
  } catch (const NumericalError& e) {
    std::cerr << info.name << ": numerical failure: " << e.what() << "\n";
    remove_failed_output();
    return 3;
  } catch (const std::bad_alloc&) {
    std::cerr << info.name << ": internal error: out of memory (the run's memory estimate passed the limit: "
              << "lower SOFTSIM_MEMORY_LIMIT_MB to what this machine can give)\n";
    remove_failed_output();
    return 1;
  } catch (const std::exception& e) {
    std::cerr << info.name << ": internal error: " << e.what() << "\n";
    remove_failed_output();
    return 1;
  }
}

}  // namespace softsim::app
