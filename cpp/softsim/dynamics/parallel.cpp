#include "softsim/dynamics/parallel.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace softsim::dynamics::detail {

namespace {

// Shared by every engine of the process: it describes the machine, not one engine.
std::atomic<long long> solo_until_ns{0};  // runs starting before this time go on one thread
std::atomic<int> backoff{1};              // grows while the team keeps losing
std::atomic<bool> warned{false};

}  // namespace

bool adaptive() {
  static const bool on = [] {
    const char* v = std::getenv("SOFTSIM_ADAPTIVE_THREADS");
    return !(v && std::strcmp(v, "0") == 0);
  }();
  return on;
}

long long clock_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

int threads_for_next_run(int requested, long long now_ns) {
  if (requested <= 1) return 1;
#if defined(SOFTSIM_HAVE_OPENMP)
  if (requested > omp_get_num_procs() && !warned.exchange(true))
    std::fprintf(stderr,
                 "softsim: %d threads asked for on %d available cores: steps wait at their barriers for "
                 "descheduled threads; use threads <= cores\n",
                 requested, omp_get_num_procs());
#endif
  if (!adaptive()) return requested;
  return now_ns < solo_until_ns.load(std::memory_order_relaxed) ? 1 : requested;
}

void record_team_run(int threads, long long wall_ns, long long waited_ns, long long end_ns) {
  // A run without barrier waits (no barrier() in its body) says nothing either way.
  if (!adaptive() || wall_ns <= 0 || waited_ns <= 0) return;
  // The threads' work summed (threads × wall − waits) below one wall time: one thread would
  // have done it faster.
  const bool lost = waited_ns > static_cast<long long>(threads - 1) * wall_ns;
  if (lost) {
    // Alone for 8 × backoff times the lost run's length: the next trial of the team costs at
    // most 1/8 of the time spent alone, less as the back-off grows.
    const int b = backoff.load(std::memory_order_relaxed);
    solo_until_ns.store(end_ns + kSoloRunsPerLoss * b * wall_ns, std::memory_order_relaxed);
    backoff.store(std::min(2 * b, kMaxBackoff), std::memory_order_relaxed);
  } else {
    backoff.store(1, std::memory_order_relaxed);
  }
}

}  // namespace softsim::dynamics::detail
