#include "softsim/multirate/probe_signal.hpp"

#include <algorithm>
#include <cmath>

namespace softsim::multirate {

double ProbeSignal::position(double t) const {
  constexpr double kTwoPi = 6.283185307179586;
  switch (kind) {
    case Kind::kChirp:
      return amplitude * std::sin(kTwoPi * (start_frequency * t + 0.5 * (end_frequency - start_frequency) * t * t / sweep_time));
    case Kind::kStep:
      return t >= start_time ? amplitude : 0.0;
    case Kind::kRampHold:
      return amplitude * std::clamp((t - start_time) / ramp_time, 0.0, 1.0);
    case Kind::kGrowingSine:
      return amplitude * std::min(t / sweep_time, 1.0) * std::sin(kTwoPi * start_frequency * t);
  }
  return 0.0;
}

double ProbeSignal::frequency(double t) const {
  switch (kind) {
    case Kind::kChirp:
      return start_frequency + (end_frequency - start_frequency) * t / sweep_time;
    case Kind::kGrowingSine:
      return start_frequency;
    default:
      return 0.0;
  }
}

}  // namespace softsim::multirate
