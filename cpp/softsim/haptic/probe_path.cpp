#include "softsim/haptic/probe_path.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

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

bool parse_probe_line(std::string line, const std::string& where, double v[4]) {
  const auto hash = line.find('#');
  if (hash != std::string::npos) line.erase(hash);
  if (line.find_first_not_of(" \t\r") == std::string::npos) return false;
  std::istringstream fields(line);
  std::string token;
  int n = 0;
  while (fields >> token) {
    if (n == 4) throw InputError(where + ": expected 4 numbers \"t x y z\", got more");
    char* end = nullptr;
    v[n] = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0') throw InputError(where + ": expected a number, got \"" + token + "\"");
    if (!std::isfinite(v[n])) throw InputError(where + ": expected a finite number, got \"" + token + "\"");
    ++n;
  }
  if (n != 4) throw InputError(where + ": expected 4 numbers \"t x y z\", got " + std::to_string(n));
  return true;
}

RecordedPath read_recorded_path(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the recorded probe trajectory");
  RecordedPath r;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    double v[4];
    const std::string where = path + ":" + std::to_string(line_no);
    if (!parse_probe_line(line, where, v)) continue;
    if (!r.time.empty() && !(v[0] > r.time.back()))
      throw InputError(where + ": expected a time after " + std::to_string(r.time.back()) + " s (times must increase)");
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
