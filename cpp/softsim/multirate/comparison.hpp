#pragma once
// One experiment of 001 §6: the same probe input through the haptic loop on
//   - the whole model at the haptic rate,
//   - the asynchronous regions (optional),
//   - the exact solution of the same discrete system (optional),
// with the force errors, peak forces and the run time per frame of whole and asynchronous
// solves measured in the same process (reported as a ratio: the speed gain).
#include <functional>
#include <optional>

#include "softsim/multirate/async_solver.hpp"
#include "softsim/multirate/force_metrics.hpp"
#include "softsim/multirate/haptic_loop.hpp"
#include "softsim/multirate/linear_model.hpp"
#include "softsim/multirate/probe_signal.hpp"

namespace softsim::multirate {

struct ComparisonSpec {
  int contact_free_node = 0;
  SolverSpec whole_solver;
  LinearSolverKind linear_solver = LinearSolverKind::kSparse;
  bool enforce_stability_limit = true;
  std::optional<AsyncRegionsSpec> async;  // run with the loop's frame step and the two settings above
  bool reference = true;
  ProbeSignal signal;
  HapticLoopSpec loop;
  int timing_repeats = 3;          // each timed loop runs this often; the fastest run counts
  double frequency_bin = 0.5;      // Hz, for error_by_frequency of periodic inputs
  // Frames done over all loops of the run (of total_loop_frames) and the simulated time of the
  // current loop, every kProgressFrames frames; empty: never.
  std::function<void(long long, double)> progress;
};

// Frames the run steps in all: every timed repeat of whole and regions, and the reference.
long long total_loop_frames(const ComparisonSpec& spec);

struct SignalSummary {
  double peak_force = 0.0;               // N
  double seconds_per_frame = 0.0;        // s, fastest of the timed repeats
  double max_second_difference = 0.0;    // N, force jump indicator
};

struct ComparisonResult {
  LoopRecord whole, async, exact;
  SignalSummary whole_summary, async_summary, exact_summary;
  ForceError whole_vs_exact, async_vs_whole, async_vs_exact;
  FrequencyBins whole_vs_exact_bins, async_vs_whole_bins, async_vs_exact_bins;
  std::vector<double> frequency;         // instantaneous input frequency per frame (Hz)
  double loop_spectral_radius = 0.0;     // exact closed loop; < 1 means a stable coupling
  double explicit_limit = 0.0;           // smallest explicit stability limit in use (inf: none)
  int async_blocks = 0;                  // factorised region blocks (adaptive sizes)
};

// The static compliance of the contact node, (K^-1)_cc projected on `direction`: the quasi-
// static haptic loop f = k_s (p - u_c) on a static model converges only if k_s times it < 1.
double contact_compliance(const ReducedSystem& system, int contact_free_node, const Eigen::VectorXd& direction);

// Throws SetupError blaming the probe stiffness for a static whole model whose loop cannot
// converge (k_s * compliance >= 1), and blaming a solver for an explicit step above its limit.
ComparisonResult run_comparison(const ReducedSystem& system, const ComparisonSpec& spec);

}  // namespace softsim::multirate
