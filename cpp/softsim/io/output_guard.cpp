#include "softsim/io/output_guard.hpp"

#include <filesystem>
#include <mutex>

#include "softsim/io/errors.hpp"

namespace softsim::io {

namespace fs = std::filesystem;

namespace {

struct Registry {
  std::mutex mutex;
  std::vector<std::string> inputs;
  std::vector<std::string> written;
};

Registry& registry() {
  static Registry r;
  return r;
}

}  // namespace

void guard_input(const std::string& path) {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  r.inputs.push_back(path);
}

void check_output_path(const std::string& path, const std::string& label) {
  const std::string name = label.empty() ? path : label;
  if (path.empty()) throw InputError((label.empty() ? std::string("output") : label) + ": expected a file name, got an empty string");
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows links: a link to /dev/null is /dev/null
  if (fs::is_directory(st)) throw InputError(name + ": expected a file name, got a directory");
  if (fs::exists(st) && !fs::is_regular_file(st))
    throw InputError(name + ": expected a regular file or a new file name, got a device or special file");
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  for (const std::string& input : r.inputs) {
    std::error_code eq;
    if (fs::equivalent(input, path, eq) && !eq)
      throw InputError(name + ": expected an output file other than the input " + input);
  }
}

void record_written(const std::string& path) {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  for (const std::string& w : r.written)
    if (w == path) return;
  r.written.push_back(path);
}

std::vector<std::string> written_files() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  return r.written;
}

void reset_output_guard() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  r.inputs.clear();
  r.written.clear();
}

ScopedInputGuard::ScopedInputGuard(std::vector<std::string> paths) : paths_(std::move(paths)) {
  for (const std::string& p : paths_) guard_input(p);
}

ScopedInputGuard::~ScopedInputGuard() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  for (const std::string& p : paths_)
    for (auto it = r.inputs.begin(); it != r.inputs.end(); ++it)
      if (*it == p) {
        r.inputs.erase(it);
        break;
      }
}

}  // namespace softsim::io
