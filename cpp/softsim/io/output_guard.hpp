#pragma once
// What a run may write, and what it wrote. Every output file goes through write_file_atomic,
// which asks check_output_path first and records the file once it is in place, so the rules
// hold for every file a tool writes (--out, VTU snapshots, .pvd series), not only for --out:
//   - an output is a regular file or a new name: a directory, a device (/dev/null), a FIFO or a
//     socket is refused, never replaced;
//   - an output is none of the run's inputs (the config, the mesh, a dataset: guard_input);
//   - a failed run removes exactly the files it put in place (written_files), nothing else.
#include <string>
#include <vector>

namespace softsim::io {

// Marks a file the run reads: writing over it is an InputError.
void guard_input(const std::string& path);
// InputError naming `label` (e.g. "config.json: /output/vtu"; `path` itself when empty) when the path may
// not be written: a directory or special file, or a guarded input.
void check_output_path(const std::string& path, const std::string& label = "");
void record_written(const std::string& path);
// The files put in place since the last reset, in order.
std::vector<std::string> written_files();
void reset_output_guard();

// Guards `paths` as inputs for its lifetime (a library call such as the Python API's, which has
// no run_app around it).
class ScopedInputGuard {
 public:
  explicit ScopedInputGuard(std::vector<std::string> paths);
  ~ScopedInputGuard();
  ScopedInputGuard(const ScopedInputGuard&) = delete;
  ScopedInputGuard& operator=(const ScopedInputGuard&) = delete;

 private:
  std::vector<std::string> paths_;
};

}  // namespace softsim::io
