#pragma once
// Thin OpenMP helpers of the explicit engine: run a body on N threads (inline without OpenMP)
// and a barrier between its phases, built so that extra threads never make a step slower.
//
// The engine's results do not depend on the thread count (every element and node is computed
// by the same instructions however the work is split; fem/element_set.hpp), so the body may run
// on fewer threads than asked without changing a bit. That is what lets a busy machine degrade
// gracefully:
//  - barrier(): spins briefly (the partner is usually a few microseconds behind), then yields
//    the core instead of spinning on (OpenMP's default barrier spins for up to ~300k iterations,
//    which on an oversubscribed machine steals the very core the late thread waits for);
//  - parallel(): measures how long each team run's threads spent waiting at the barriers. If
//    the waits sum to more than (threads − 1) × the run's wall time, the threads' work summed is
//    less than the wall time: they are rarely scheduled together and one thread would be faster.
//    The runs of the next while then go on one thread, and the team is tried again after a
//    back-off that grows while it keeps losing and resets when it wins (below). Set
//    SOFTSIM_ADAPTIVE_THREADS=0 to always use the team.
//  - asking for more threads than the cores OpenMP reports prints one warning line to stderr.
// What a user should set: `threads` ≤ physical cores; nothing else is needed. OMP_WAIT_POLICY and
// GOMP_SPINCOUNT still govern the pool between runs and the end of a run (cpp/apps/dhd_sim.md).
#include <atomic>
#include <chrono>
#include <thread>

#if defined(SOFTSIM_HAVE_OPENMP)
#include <omp.h>
#endif

namespace softsim::dynamics::detail {

// A sense-counting barrier for one team; barrier() finds it through a thread-local pointer set
// when the team starts, so concurrent teams (several engines) do not share one.
struct TeamBarrier {
  explicit TeamBarrier(int n) : size(n) {}
  const int size;
  std::atomic<int> arrived{0};
  std::atomic<unsigned> generation{0};
  std::atomic<long long> waited_ns{0};  // summed over threads
};

inline thread_local TeamBarrier* current_team = nullptr;

// Spins before yielding: about the time a balanced partner needs to arrive on a quiet machine.
inline constexpr int kBarrierSpins = 4000;

inline void wait_at(TeamBarrier& b) {
  const unsigned gen = b.generation.load(std::memory_order_acquire);
  if (b.arrived.fetch_add(1, std::memory_order_acq_rel) == b.size - 1) {
    b.arrived.store(0, std::memory_order_relaxed);
    b.generation.fetch_add(1, std::memory_order_release);
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < kBarrierSpins; ++i) {
    if (b.generation.load(std::memory_order_acquire) != gen) break;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  while (b.generation.load(std::memory_order_acquire) == gen) std::this_thread::yield();
  const auto waited = std::chrono::steady_clock::now() - t0;
  b.waited_ns.fetch_add(std::chrono::duration_cast<std::chrono::nanoseconds>(waited).count(),
                        std::memory_order_relaxed);
}

// The team-size decision (parallel.cpp): how many threads a run starting at `now_ns` gets, and
// the verdict on a team run that ended at `end_ns` after `wall_ns`, with `waited_ns` of barrier
// waits summed over its `threads`. A lost run sends the runs of the next 8 × backoff × its
// length to one thread; the backoff doubles per loss up to 32 and resets with a won run.
inline constexpr long long kSoloRunsPerLoss = 8;
inline constexpr int kMaxBackoff = 32;
int threads_for_next_run(int requested, long long now_ns);
void record_team_run(int threads, long long wall_ns, long long waited_ns, long long end_ns);
long long clock_ns();  // steady clock
// False where SOFTSIM_ADAPTIVE_THREADS=0: every run gets the threads asked for.
bool adaptive();

// Runs body(thread, threads) on up to `threads` OpenMP threads (or inline without OpenMP).
template <class Body>
void parallel(int threads, Body&& body) {
#if defined(SOFTSIM_HAVE_OPENMP)
  const long long t0 = clock_ns();
  const int team = threads_for_next_run(threads, t0);
  if (team > 1) {
    TeamBarrier b(team);
    int started = team;
#pragma omp parallel num_threads(team)
    {
      // The runtime may give fewer threads than asked: the barrier counts those that came.
#pragma omp single
      started = omp_get_num_threads();
      TeamBarrier* previous = current_team;
      current_team = &b;
      if (started == team) {
        body(omp_get_thread_num(), team);
      } else if (omp_get_thread_num() == 0) {
        current_team = nullptr;
        body(0, 1);
      }
      current_team = previous;
    }
    const long long t1 = clock_ns();
    if (started == team) record_team_run(team, t1 - t0, b.waited_ns.load(std::memory_order_relaxed), t1);
    return;
  }
#endif
  body(0, 1);
}

// Inside parallel()'s body: every thread of the team waits here for the others (no-op alone).
inline void barrier() {
  if (current_team) wait_at(*current_team);
}

}  // namespace softsim::dynamics::detail
