#include "common/progress_line.hpp"

#include <unistd.h>

#include <cstdio>

namespace softsim::app {

ProgressLine::ProgressLine(std::string tool, long long total, std::string unit)
    : tool_(std::move(tool)), unit_(std::move(unit)), total_(total), enabled_(isatty(STDERR_FILENO) == 1) {
  start_ = last_ = Clock::now();
}

ProgressLine::~ProgressLine() {
  if (drawn_) std::fputc('\n', stderr);
}

void ProgressLine::update(long long done, double time) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (now - last_ < std::chrono::milliseconds(500) && done < total_) return;
  last_ = now;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r%s: %s %lld / %lld (t = %.6g s), %.0f %ss/s   ", tool_.c_str(), unit_.c_str(), done, total_,
               time, seconds > 0 ? static_cast<double>(done) / seconds : 0.0, unit_.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace softsim::app
