#include "softsim/multirate/comparison.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "softsim/io/errors.hpp"
#include "softsim/multirate/exact_reference.hpp"
#include "softsim/multirate/setup_error.hpp"
#include "softsim/multirate/whole_model.hpp"

namespace softsim::multirate {

namespace {

double timed_run(FrameStepper& stepper, const ProbeSignal& signal, const HapticLoopSpec& loop, LoopRecord& record,
                 const std::function<void(long long, double)>& progress, long long& frames_done) {
  stepper.reset();
  HapticLoopSpec loop_spec = loop;  // progress counted over every loop of the run
  if (progress) {
    const long long before = frames_done;
    loop_spec.progress = [&progress, before](long n, double t) { progress(before + n, t); };
  }
  frames_done += loop.frames;
  const auto start = std::chrono::steady_clock::now();
  run_haptic_loop(stepper, signal, loop_spec, record);
  const auto stop = std::chrono::steady_clock::now();
  return std::chrono::duration<double>(stop - start).count() / static_cast<double>(loop.frames);
}

SignalSummary summarise(const LoopRecord& record, double seconds_per_frame) {
  SignalSummary s;
  s.peak_force = peak_abs(record.force);
  s.seconds_per_frame = seconds_per_frame;
  s.max_second_difference = max_second_difference(record.force);
  return s;
}

}  // namespace

double contact_compliance(const ReducedSystem& system, int contact_free_node, const Eigen::VectorXd& direction) {
  const int p = system.dofs_per_node;
  const std::shared_ptr<const StiffnessLdlt> ldlt = factorised_stiffness(system);
  if (ldlt->info() != Eigen::Success) throw NumericalError("contact compliance: stiffness factorisation failed");
  Eigen::VectorXd f = Eigen::VectorXd::Zero(system.num_dofs());
  const Eigen::VectorXd e = direction.normalized();
  f.segment(contact_free_node * p, p) = e;
  const Eigen::VectorXd u = ldlt->solve(f);
  return e.dot(u.segment(contact_free_node * p, p));
}

long long total_loop_frames(const ComparisonSpec& spec) {
  const long long loops = std::max(1, spec.timing_repeats) * (spec.async ? 2LL : 1LL) + (spec.reference ? 1 : 0);
  return loops * spec.loop.frames;
}

ComparisonResult run_comparison(const ReducedSystem& system, const ComparisonSpec& spec) {
  ComparisonResult result;
  const HapticLoopSpec& loop = spec.loop;
  if (spec.whole_solver.kind == SolverKind::kStatic) {
    const double gain = loop.probe_stiffness * contact_compliance(system, spec.contact_free_node, loop.direction);
    if (gain >= 1.0) {
      std::ostringstream msg;
      msg << "static solver: the haptic loop diverges, probe stiffness x contact compliance = " << gain
          << " >= 1 (the probe spring must be softer than the model at the contact node)";
      throw SetupError({SettingAtFault::Kind::kProbeStiffness}, msg.str());
    }
  }

  WholeModel whole(system, spec.contact_free_node, spec.whole_solver, loop.frame_step, spec.linear_solver,
                   spec.enforce_stability_limit);
  result.explicit_limit = whole.block().stability_limit();
  std::unique_ptr<AsyncSolver> async;
  if (spec.async) {
    const AsyncSpec a{*spec.async, loop.frame_step, spec.linear_solver, spec.enforce_stability_limit};
    async = std::make_unique<AsyncSolver>(system, spec.contact_free_node, a);
    result.explicit_limit = std::min(result.explicit_limit, async->smallest_stability_limit());
    result.async_blocks = async->blocks();
  }

  // Whole and asynchronous runs alternate so that slow drifts of the machine hit both alike.
  const int repeats = std::max(1, spec.timing_repeats);
  long long frames_done = 0;
  double whole_best = std::numeric_limits<double>::infinity();
  double async_best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeats; ++r) {
    whole_best = std::min(whole_best, timed_run(whole, spec.signal, loop, result.whole, spec.progress, frames_done));
    if (async) async_best = std::min(async_best, timed_run(*async, spec.signal, loop, result.async, spec.progress, frames_done));
  }
  result.whole_summary = summarise(result.whole, whole_best);
  if (async) result.async_summary = summarise(result.async, async_best);

  result.frequency.resize(result.whole.force.size());
  for (std::size_t n = 0; n < result.frequency.size(); ++n)
    result.frequency[n] = spec.signal.frequency(static_cast<double>(n) * loop.frame_step);
  const bool periodic =
      spec.signal.kind == ProbeSignal::Kind::kChirp || spec.signal.kind == ProbeSignal::Kind::kGrowingSine;

  if (spec.reference) {
    ExactReference exact(system, spec.contact_free_node, loop.frame_step);
    result.loop_spectral_radius = exact.loop_spectral_radius(loop.probe_stiffness);
    const double seconds = timed_run(exact, spec.signal, loop, result.exact, spec.progress, frames_done);
    result.exact_summary = summarise(result.exact, seconds);
    result.whole_vs_exact = force_error(result.whole.force, result.exact.force);
    if (periodic)
      result.whole_vs_exact_bins = error_by_frequency(result.whole.force, result.exact.force, result.frequency, spec.frequency_bin);
    if (async) {
      result.async_vs_exact = force_error(result.async.force, result.exact.force);
      if (periodic)
        result.async_vs_exact_bins =
            error_by_frequency(result.async.force, result.exact.force, result.frequency, spec.frequency_bin);
    }
  }
  if (async) {
    result.async_vs_whole = force_error(result.async.force, result.whole.force);
    if (periodic)
      result.async_vs_whole_bins = error_by_frequency(result.async.force, result.whole.force, result.frequency, spec.frequency_bin);
  }
  return result;
}

}  // namespace softsim::multirate
