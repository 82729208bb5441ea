#include "softsim/io/output_guard.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <mutex>
#include <utility>

#include "softsim/io/errors.hpp"

namespace softsim::io {

namespace fs = std::filesystem;

namespace {

struct Registry {
  std::mutex mutex;
  std::vector<std::string> inputs;
  std::vector<std::string> written;
  std::vector<std::pair<std::string, std::string>> kept;  // (path, the earlier file's copy)
  bool in_run = false;  // earlier files are kept only inside a run that will commit or undo
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

namespace {

void check_path(const std::string& path, const std::string& label, bool pipe_allowed) {
  const std::string name = label.empty() ? path : label;
  if (path.empty()) throw InputError((label.empty() ? std::string("output") : label) + ": expected a file name, got an empty string");
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows links: a link to /dev/null is /dev/null
  if (fs::is_directory(st)) throw InputError(name + ": expected a file name, got a directory");
  if (fs::exists(st) && !fs::is_regular_file(st) && !(pipe_allowed && fs::is_fifo(st)))
    throw InputError(name + (pipe_allowed ? ": expected a regular file, a named pipe or a new file name, got a device or special file"
                                          : ": expected a regular file or a new file name, got a device or special file"));
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  for (const std::string& input : r.inputs) {
    std::error_code eq;
    if (fs::equivalent(input, path, eq) && !eq)
      throw InputError(name + ": expected an output file other than the input " + input);
  }
}

}  // namespace

void check_output_path(const std::string& path, const std::string& label) { check_path(path, label, false); }

void check_stream_path(const std::string& path, const std::string& label) { check_path(path, label, true); }

void keep_previous(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(path, ec))) return;
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  if (!r.in_run) return;
  for (const std::string& w : r.written)
    if (w == path) return;
  for (const auto& k : r.kept)
    if (k.first == path) return;
  const std::string copy = path + ".prev." + std::to_string(::getpid());
  std::remove(copy.c_str());
  if (::link(path.c_str(), copy.c_str()) != 0) {
    std::error_code cp;
    if (!fs::copy_file(path, copy, fs::copy_options::overwrite_existing, cp) || cp) return;
  }
  r.kept.emplace_back(path, copy);
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

void undo_written() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  for (const std::string& w : r.written) std::remove(w.c_str());
  for (const auto& k : r.kept) std::rename(k.second.c_str(), k.first.c_str());
  r.written.clear();
  r.kept.clear();
}

void commit_written() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  for (const auto& k : r.kept) std::remove(k.second.c_str());
  r.kept.clear();
}

void reset_output_guard() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  r.inputs.clear();
  r.written.clear();
  r.kept.clear();
  r.in_run = true;
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
