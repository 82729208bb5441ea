#include "softsim/multirate/run_memory.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "softsim/io/errors.hpp"
#include "softsim/io/limits.hpp"

namespace softsim::multirate {

namespace {

// A number kept in the artifact: its JSON value and its text in the written document
// (the same allowance as rpim_precompute's datasets).
constexpr double kBytesPerJsonNumber = 60.0;

bool binned(const ProbeSignal& s) {
  return s.kind == ProbeSignal::Kind::kChirp || s.kind == ProbeSignal::Kind::kGrowingSine;
}

int loops_recorded(const ComparisonSpec& spec) { return 1 + (spec.async ? 1 : 0) + (spec.reference ? 1 : 0); }

// Bins of the error-by-frequency tables (force_metrics.hpp), as read_run_config bounds them.
double frequency_bins(const ComparisonSpec& spec) {
  if (!binned(spec.signal) || !(spec.reference || spec.async)) return 0.0;
  const double last = static_cast<double>(spec.loop.frames - 1) * spec.loop.frame_step;
  const double top = std::max({0.0, spec.signal.frequency(0.0), spec.signal.frequency(last)});
  return std::floor(top / spec.frequency_bin) + 1.0;
}

}  // namespace

std::vector<MemoryShare> estimate_run_memory(const RunConfig& config) {
  const ComparisonSpec& spec = config.comparison;
  const double frames = static_cast<double>(spec.loop.frames);
  const double n = static_cast<double>(config.bar.nodes - 1);  // free DOFs of the bar
  const int loops = loops_recorded(spec);
  std::vector<MemoryShare> shares;

  // LoopRecord: probe, force, contact (double) and primary size (int) per frame and loop, and
  // the input frequency per frame (comparison.hpp).
  shares.push_back({"/haptics/duration", "the per-frame records of " + std::to_string(loops) + " loops",
                    frames * (28.0 * loops + 8.0)});

  if (config.series_every > 0) {
    // time, probe, force and contact of the whole model, frequency; 3 of the regions; 2 exact.
    const double signals = 5.0 + (spec.async ? 3.0 : 0.0) + (spec.reference ? 2.0 : 0.0);
    const double kept = std::ceil(frames / config.series_every);
    shares.push_back({"/series_every", "the time series in the artifact",
                      frames * 8.0 + kept * signals * kBytesPerJsonNumber});
  }

  const double bins = frequency_bins(spec);
  if (bins > 0) {
    const int tables = (spec.reference ? 1 : 0) + (spec.async ? 1 : 0) + (spec.async && spec.reference ? 1 : 0);
    // Accumulators (3 x 8 bytes a bin) while binning, then 3 numbers a bin kept and written.
    shares.push_back({"/frequency_bin", "the error-by-frequency tables",
                      bins * (24.0 + tables * 3.0 * (8.0 + kBytesPerJsonNumber))});
  }

  if (spec.linear_solver == LinearSolverKind::kDense) {
    // A dense Cholesky holds the matrix and its factor (spd_solver.cpp), for the whole model and
    // for each region block; an adaptive primary region factorises one block per size, each at
    // most the model's size.
    double blocks = 1.0;
    if (spec.async)
      blocks += spec.async->primary.adaptive()
                    ? 2.0 * (spec.async->primary.max_nodes - spec.async->primary.min_nodes + 1)
                    : 1.0;
    shares.push_back({"/linear_solver", "the dense factorisations", blocks * 2.0 * n * n * 8.0});
  }

  if (spec.reference) {
    // Van Loan's block matrix of size 2n + 1, the matrix exponential's work matrices, the
    // transition matrix and the closed loop's eigenvalue problem: about a dozen of that size.
    const double m = 2.0 * n + 1.0;
    shares.push_back({"/reference", "the exact reference's dense matrices", 12.0 * m * m * 8.0});
  }
  return shares;
}

double estimate_run_work(const RunConfig& config) {
  const ComparisonSpec& spec = config.comparison;
  const double frames = static_cast<double>(spec.loop.frames);
  const double elements = static_cast<double>(config.bar.nodes - 1);
  const double timed_loops = std::max(1, spec.timing_repeats) * (spec.async ? 2.0 : 1.0);
  const double reference = spec.reference ? 4.0 * elements * elements / 32.0 : 0.0;
  return frames * (timed_loops * elements + reference);
}

void require_run_resources(const RunConfig& config) {
  const std::vector<MemoryShare> shares = estimate_run_memory(config);
  double total = 0.0;
  for (const MemoryShare& s : shares) total += s.bytes;
  const MemoryShare& largest =
      *std::max_element(shares.begin(), shares.end(), [](const auto& a, const auto& b) { return a.bytes < b.bytes; });
  io::require_memory(largest.pointer, total, "the run (mostly " + largest.what + ")");

  const double work = estimate_run_work(config);
  const double limit = io::max_element_updates();
  if (work > limit) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "expected a run of at most %.3g element updates (SOFTSIM_MAX_ELEMENT_UPDATES; this one needs %.3g)",
                  limit, work);
    throw ConfigInputError("/haptics/duration", text);
  }
}

}  // namespace softsim::multirate
