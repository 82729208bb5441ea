#pragma once
// What a run may write, and what it wrote. Every output file goes through write_file_atomic,
// which asks check_output_path first and records the file once it is in place, so the rules
// hold for every file a tool writes (--out, VTU snapshots, .pvd series), not only for --out:
//   - an output is a regular file or a new name: a directory, a device (/dev/null), a FIFO or a
//     socket is refused, never replaced;
//   - an output is none of the run's inputs (the config, the mesh, a dataset: guard_input);
//   - a failed run removes exactly the files it put in place (written_files), nothing else, and
//     puts back an earlier run's file that one of them replaced (keep_previous: a failed run of
//     a VTU series never leaves a mixed series or deletes the earlier .pvd);
//   - a stream written in place (haptic_sim's visual stream) may also be a named pipe, which is
//     never removed (check_stream_path).
#include <string>
#include <vector>

namespace softsim::io {

// Marks a file the run reads: writing over it is an InputError.
void guard_input(const std::string& path);
// InputError naming `label` (e.g. "config.json: /output/vtu"; `path` itself when empty) when the path may
// not be written: a directory or special file, or a guarded input.
void check_output_path(const std::string& path, const std::string& label = "");
// The rules of check_output_path for a file written in place as the run goes (a stream a reader
// follows): a named pipe is allowed too.
void check_stream_path(const std::string& path, const std::string& label);
// Before this run first replaces `path`: an earlier file there is kept aside (a hard link, or a
// copy where links are not possible) until the run ends. Nothing for a new name or a file this
// run wrote already.
void keep_previous(const std::string& path);
void record_written(const std::string& path);
// The files put in place since the last reset, in order.
std::vector<std::string> written_files();
// A failed run: removes the files it put in place and puts back the earlier files they replaced.
void undo_written();
// A finished run: drops the earlier files kept aside.
void commit_written();
// A run starts (a tool's entry): nothing guarded or written yet; from now on earlier files are
// kept aside until commit_written or undo_written.
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
