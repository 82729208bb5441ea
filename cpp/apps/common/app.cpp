#include "common/app.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "softsim/io/errors.hpp"
#include "softsim/io/git_commit.hpp"
#include "softsim/io/sha256.hpp"
#include "softsim/version.hpp"

namespace softsim::app {

std::string AppContext::input(const std::string& path) {
  provenance.input_sha256[path] = io::sha256_file(path);
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

// A failed run removes its --out file, so that no stale artifact is left behind. An --out that
// names a directory, the config or an input named in the config is refused instead (the failure
// would otherwise delete the user's file, and success overwrite it): the conflict, or "".
std::string out_path_conflict(const AppContext& ctx) {
  std::error_code ec;
  if (std::filesystem::is_directory(ctx.out_path, ec))
    return "command line: --out " + ctx.out_path + ": expected a file name, got a directory";
  if (!ctx.config_path.empty() && same_file(ctx.config_path, ctx.out_path))
    return "command line: --out " + ctx.out_path + ": expected a file other than the --config file";
  if (!ctx.config_json.is_object()) return "";
  const nlohmann::json members = ctx.config_json.flatten();  // keys are JSON pointers
  for (auto it = members.begin(); it != members.end(); ++it)
    if (it->is_string() && same_file(it->get<std::string>(), ctx.out_path))
      return ctx.config_path + ": " + it.key() + ": expected a file other than the --out file " + ctx.out_path;
  return "";
}

void remove_failed_output(const AppContext& ctx) {
  if (!ctx.out_path.empty() && out_path_conflict(ctx).empty()) std::remove(ctx.out_path.c_str());
}

}  // namespace

int run_app(int argc, char** argv, const AppInfo& info,
            const std::function<void(AppContext&)>& body) {
  AppContext ctx;
  ctx.provenance.tool = info.name;
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
    return 0;
  } catch (const InputError& e) {
    std::cerr << info.name << ": error: ";
    // A config member found at fault after reading knows its JSON pointer but not the file.
    if (const auto* at = dynamic_cast<const ConfigInputError*>(&e))
      std::cerr << ctx.config_path << ": " << at->pointer << ": ";
    std::cerr << e.what() << "\n";
    remove_failed_output(ctx);
    return 2;
  } catch (const NumericalError& e) {
    std::cerr << info.name << ": numerical failure: " << e.what() << "\n";
    remove_failed_output(ctx);
    return 3;
  } catch (const std::exception& e) {
    std::cerr << info.name << ": internal error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace softsim::app
