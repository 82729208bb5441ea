#include "softsim/io/atomic_file.hpp"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>
#include <unistd.h>

#include "softsim/io/errors.hpp"
#include "softsim/io/limits.hpp"
#include "softsim/io/output_guard.hpp"

namespace softsim::io {

namespace {

// Removes "<name>.tmp.<pid>" siblings of `path` whose writer is gone (killed mid-write: the
// temporary of a large artifact would otherwise stay for ever). A live writer's is left alone.
void remove_stale_temporaries(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const std::string prefix = target.filename().string() + ".tmp.";
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) continue;
    const auto pid = static_cast<pid_t>(std::stol(digits));
    if (pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH) {
      std::error_code rm;
      fs::remove(it->path(), rm);
    }
  }
}

}  // namespace

void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& writer) {
  check_output_path(path);
  remove_stale_temporaries(path);
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path + ": cannot write output file");
    errno = 0;
    try {
      writer(out);
    } catch (...) {
      out.close();
      std::remove(tmp.c_str());
      throw;
    }
    out.flush();
    if (!out) {
      // errno of the failed write: a full disk, or the file-size limit (SIGXFSZ is ignored).
      const std::string why = errno ? std::string(": ") + std::strerror(errno) : std::string();
      std::remove(tmp.c_str());
      throw InputError(path + ": write failed" + why);
    }
  }
  keep_previous(path);  // an earlier run's file comes back if this run fails
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError(path + ": cannot rename temporary file into place");
  }
  record_written(path);
}

void write_file_atomic(const std::string& path, const std::string& content) {
  write_file_atomic(path, [&](std::ostream& out) { out << content; });
}

std::uint64_t require_input_file(const std::string& path) {
  if (path.empty()) throw InputError("expected a file name, got an empty string");
  // Only a regular file has an end: a device (/dev/zero, /dev/urandom), a FIFO or a directory
  // would be read until memory runs out, or block for ever.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw InputError(path + ": cannot open file");
  if (!S_ISREG(st.st_mode))
    throw InputError(path + ": expected a regular file, got " +
                     (S_ISDIR(st.st_mode) ? "a directory" : S_ISFIFO(st.st_mode) ? "a pipe" : "a device or special file"));
  const std::uint64_t limit = max_input_bytes();
  if (static_cast<std::uint64_t>(st.st_size) > limit)
    throw InputError(path + ": expected a file of at most " + format_bytes(static_cast<double>(limit)) +
                     " (SOFTSIM_MAX_INPUT_MB), got " + format_bytes(static_cast<double>(st.st_size)));
  return static_cast<std::uint64_t>(st.st_size);
}

std::string read_text_file(const std::string& path) {
  const std::uint64_t size = require_input_file(path);
  const std::uint64_t limit = max_input_bytes();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open file");
  // The size is checked again while reading: a file that grows (or reports no size, as /proc
  // does) is cut off at the limit rather than read without end.
  std::string text;
  text.reserve(static_cast<std::size_t>(size));
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > limit)
      throw InputError(path + ": expected a file of at most " + format_bytes(static_cast<double>(limit)) +
                       " (SOFTSIM_MAX_INPUT_MB), got more");
  }
  if (in.bad()) throw InputError(path + ": read failed");
  return text;
}

}  // namespace softsim::io
