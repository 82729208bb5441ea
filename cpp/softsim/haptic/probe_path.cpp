#include "softsim/haptic/probe_path.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string_view>

#include "softsim/io/errors.hpp"

namespace softsim::haptic {

Eigen::Vector3d RecordedPath::at(double t) const {
  if (t <= time.front()) return position.front();
  if (t >= time.back()) return position.back();
  const auto it = std::upper_bound(time.begin(), time.end(), t);
  const std::size_t k = static_cast<std::size_t>(it - time.begin());
  const double s = (t - time[k - 1]) / (time[k] - time[k - 1]);
  return (1 - s) * position[k - 1] + s * position[k];
}

namespace {

bool ends_token(char c) { return c == '\0' || c == '#' || c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

}  // namespace

bool parse_probe_line(const char* line, const LineSource& where, double v[4]) {
  int n = 0;
  const char* p = line;
  while (true) {
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') ++p;
    if (*p == '\0' || *p == '#') break;
    const char* end_of_token = p;
    while (!ends_token(*end_of_token)) ++end_of_token;
    const std::string_view token(p, static_cast<std::size_t>(end_of_token - p));
    if (n == 4) throw InputError(where.name() + ": expected 4 numbers \"t x y z\", got more");
    char* end = nullptr;
    v[n] = std::strtod(p, &end);
    if (end != end_of_token)
      throw InputError(where.name() + ": expected a number, got \"" + std::string(token) + "\"");
    if (!std::isfinite(v[n]))
      throw InputError(where.name() + ": expected a finite number, got \"" + std::string(token) + "\"");
    ++n;
    p = end_of_token;
  }
  if (n == 0) return false;
  if (n != 4) throw InputError(where.name() + ": expected 4 numbers \"t x y z\", got " + std::to_string(n));
  return true;
}

RecordedPath read_recorded_path(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the recorded probe trajectory");
  RecordedPath r;
  std::string line;
  const std::string prefix = path + ":";
  LineSource where{prefix, 0};
  while (std::getline(in, line)) {
    ++where.number;
    double v[4];
    if (!parse_probe_line(line.c_str(), where, v)) continue;
    if (!r.time.empty() && !(v[0] > r.time.back()))
      throw InputError(where.name() + ": expected a time after " + std::to_string(r.time.back()) + " s (times must increase)");
    r.time.push_back(v[0]);
    r.position.emplace_back(v[1], v[2], v[3]);
  }
  if (r.time.empty()) throw InputError(path + ": expected at least one line \"t x y z\"");
  return r;
}

Eigen::Vector3d ProbePath::at(double t) const {
  switch (kind) {
    case Kind::recorded:
      return recorded.at(t);
    case Kind::slide: {
      const double slid = slide_speed * std::max(0.0, t - signal.start_time - signal.ramp_time);
      return origin + signal.position(t) * direction + slid * slide_direction;
    }
    default:
      return origin + signal.position(t) * direction;
  }
}

}  // namespace softsim::haptic
