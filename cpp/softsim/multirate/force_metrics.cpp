#include "softsim/multirate/force_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "softsim/io/errors.hpp"

namespace softsim::multirate {

double peak_abs(const std::vector<double>& signal) {
  double peak = 0.0;
  for (double x : signal) peak = std::max(peak, std::abs(x));
  return peak;
}

ForceError force_error(const std::vector<double>& force, const std::vector<double>& reference) {
  if (force.size() != reference.size() || force.empty()) throw InputError("force error: signals of different length");
  ForceError e;
  double sum = 0.0;
  for (std::size_t i = 0; i < force.size(); ++i) {
    const double d = force[i] - reference[i];
    sum += d * d;
    e.peak = std::max(e.peak, std::abs(d));
  }
  e.rms = std::sqrt(sum / static_cast<double>(force.size()));
  const double ref = peak_abs(reference);
  if (ref > 0) {
    e.rms_relative = e.rms / ref;
    e.peak_relative = e.peak / ref;
  }
  return e;
}

double max_second_difference(const std::vector<double>& force, std::size_t begin, std::size_t end) {
  double worst = 0.0;
  if (end == 0 || end > force.size()) end = force.size();
  for (std::size_t n = std::max<std::size_t>(begin, 2); n < end; ++n)
    worst = std::max(worst, std::abs(force[n] - 2.0 * force[n - 1] + force[n - 2]));
  return worst;
}

FrequencyBins error_by_frequency(const std::vector<double>& force, const std::vector<double>& reference,
                                 const std::vector<double>& frequency, double bin_width) {
  if (force.size() != reference.size() || force.size() != frequency.size())
    throw InputError("force error by frequency: signals of different length");
  if (!(bin_width > 0)) throw InputError("force error by frequency: bin width must be positive");
  double top = 0.0;
  for (double f : frequency) top = std::max(top, f);
  if (!(top / bin_width <= kMaxFrequencyBins)) throw InputError("force error by frequency: more than 1e7 bins");
  const std::size_t bins = static_cast<std::size_t>(std::floor(top / bin_width)) + 1;
  std::vector<double> err(bins, 0.0), ref(bins, 0.0);
  std::vector<long> count(bins, 0);
  for (std::size_t i = 0; i < force.size(); ++i) {
    if (frequency[i] < 0) continue;
    const std::size_t b = std::min(bins - 1, static_cast<std::size_t>(frequency[i] / bin_width));
    const double d = force[i] - reference[i];
    err[b] += d * d;
    ref[b] += reference[i] * reference[i];
    ++count[b];
  }
  FrequencyBins out;
  for (std::size_t b = 0; b < bins; ++b) {
    if (count[b] == 0) continue;
    out.frequency.push_back((b + 0.5) * bin_width);
    out.rms_error.push_back(std::sqrt(err[b] / count[b]));
    out.rms_reference.push_back(std::sqrt(ref[b] / count[b]));
  }
  return out;
}

}  // namespace softsim::multirate
