#pragma once
// The probe tip's world position over time, for the haptic scene's generated inputs (001 §6:
// press and hold, the chirp of Fig. 6, the growing sine of Fig. 8; and a slide along the
// surface) and for a recorded trajectory read from a file.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/multirate/probe_signal.hpp"

namespace softsim::haptic {

// A trajectory recorded as lines "t x y z" (s, m); '#' starts a comment.
struct RecordedPath {
  std::vector<double> time;
  std::vector<Eigen::Vector3d> position;
  // Linear interpolation; held constant before the first and after the last sample.
  Eigen::Vector3d at(double t) const;
};

// Where a probe line came from, "<prefix><number>" (e.g. "stdin:12"), for an error message;
// composed only when there is an error, so the live loop allocates nothing per frame.
struct LineSource {
  const std::string& prefix;
  long number = 0;
  std::string name() const { return prefix + std::to_string(number); }
};

// One line "t x y z" (NUL-terminated; '#' starts a comment) into v. False for a blank line;
// InputError naming `where` for anything else that is not four finite numbers.
bool parse_probe_line(const char* line, const LineSource& where, double v[4]);

// Reads a recorded trajectory. InputError naming the file and line for a malformed line, a value
// that is not finite, a time that does not increase, or an empty file.
RecordedPath read_recorded_path(const std::string& path);

struct ProbePath {
  enum class Kind { press, slide, growing_sine, chirp, recorded };
  Kind kind = Kind::press;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();     // where the tip starts (m)
  Eigen::Vector3d direction = -Eigen::Vector3d::UnitZ();  // unit: into the organ
  multirate::ProbeSignal signal;                        // depth along `direction` (press: ramp-hold)
  Eigen::Vector3d slide_direction = Eigen::Vector3d::UnitX();  // unit (slide)
  double slide_speed = 0;                               // m/s, after the press's ramp (slide)
  RecordedPath recorded;

  Eigen::Vector3d at(double t) const;
};

}  // namespace softsim::haptic
