#pragma once
// Comparisons of haptic force signals (001 Tables 1-2: peak force and force error).
#include <vector>

namespace softsim::multirate {

struct ForceError {
  double rms = 0.0;            // N
  double peak = 0.0;           // N, largest |F - F_ref|
  double rms_relative = 0.0;   // rms / peak |F_ref|
  double peak_relative = 0.0;  // peak / peak |F_ref|
};

double peak_abs(const std::vector<double>& signal);

// Error of `force` against `reference` (same length), relative to the reference's peak.
ForceError force_error(const std::vector<double>& force, const std::vector<double>& reference);

// Largest |F[n] - 2 F[n-1] + F[n-2]|: the force's discrete second difference. A smooth force
// sampled every frame has second differences of order (frame step)^2; a jump of size J in the
// force shows up as a second difference of about J. The measure of the 001 §5 "force jumps".
// Over the frames [begin, end) (end = 0: to the last frame).
double max_second_difference(const std::vector<double>& force, std::size_t begin = 0, std::size_t end = 0);

// RMS force error in bins of the input's instantaneous frequency (001 Fig. 6: error vs
// frequency of a chirp). Bins [k w, (k+1) w) up to the largest frequency seen, at most
// kMaxFrequencyBins of them (InputError beyond); empty bins are dropped.
inline constexpr double kMaxFrequencyBins = 1e7;
struct FrequencyBins {
  std::vector<double> frequency;       // bin centre (Hz)
  std::vector<double> rms_error;       // N
  std::vector<double> rms_reference;   // N, RMS of the reference force in the bin
};
FrequencyBins error_by_frequency(const std::vector<double>& force, const std::vector<double>& reference,
                                 const std::vector<double>& frequency, double bin_width);

}  // namespace softsim::multirate
