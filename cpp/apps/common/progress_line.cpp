#include "common/progress_line.hpp"

#include <unistd.h>

#include <cstdio>

namespace softsim::app {

ProgressLine::ProgressLine(std::string tool, int total_steps)
    : tool_(std::move(tool)), total_(total_steps), enabled_(isatty(STDERR_FILENO) == 1) {
  start_ = last_ = Clock::now();
}

ProgressLine::~ProgressLine() {
  if (drawn_) std::fputc('\n', stderr);
}

void ProgressLine::update(int steps_done, double time) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (now - last_ < std::chrono::milliseconds(500) && steps_done < total_) return;
  last_ = now;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r%s: step %d / %d (t = %.6g s), %.0f steps/s   ", tool_.c_str(), steps_done, total_,
               time, seconds > 0 ? steps_done / seconds : 0.0);
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace softsim::app
