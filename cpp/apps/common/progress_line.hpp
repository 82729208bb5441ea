#pragma once
// A progress line for long runs on a terminal: "TOOL: step 12000 / 100000 (t = 0.012 s),
// 8450 steps/s" (or frames), rewritten in place at most every half second on stderr, and nothing at all
// when stderr is not a terminal (pipelines, CI logs, the experiment pipeline's runs).
#include <chrono>
#include <string>

namespace softsim::app {

class ProgressLine {
 public:
  ProgressLine(std::string tool, long long total, std::string unit = "step");
  ~ProgressLine();  // ends the line if one was drawn
  // Steps (frames) done so far and the simulated time (cheap when nothing is to be drawn: one
  // clock read).
  void update(long long done, double time);
  bool enabled() const { return enabled_; }

 private:
  using Clock = std::chrono::steady_clock;
  std::string tool_, unit_;
  long long total_ = 0;
  bool enabled_ = false;
  bool drawn_ = false;
  Clock::time_point start_, last_;
};

}  // namespace softsim::app
