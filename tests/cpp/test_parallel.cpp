// The explicit engine's thread helpers (dynamics/parallel.hpp): the team barrier orders phases
// (every write before it is seen by every thread after it), and the team-size decision runs one
// thread after a team run whose threads mostly waited, backing off while the team keeps losing.
#include <gtest/gtest.h>

#include <vector>

#include "softsim/dynamics/parallel.hpp"

using namespace softsim::dynamics::detail;

TEST(Parallel, BarrierMakesEveryThreadsWritesVisibleToAllAfterIt) {
#if defined(SOFTSIM_HAVE_OPENMP)
  for (int team : {2, 3}) {
    TeamBarrier b(team);
    std::vector<int> slot(team, -1);
    int mismatches = 0;
#pragma omp parallel num_threads(team) reduction(+ : mismatches)
    {
      if (omp_get_num_threads() == team) {
        current_team = &b;
        const int me = omp_get_thread_num();
        for (int phase = 0; phase < 300; ++phase) {
          slot[me] = phase;
          barrier();
          for (int t = 0; t < team; ++t) mismatches += slot[t] != phase;
          barrier();
        }
        current_team = nullptr;
      }
    }
    EXPECT_EQ(mismatches, 0) << team << " threads";
  }
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

TEST(Parallel, ATeamThatMostlyWaitedGivesWayToOneThreadWithBackOff) {
  if (!adaptive()) GTEST_SKIP() << "SOFTSIM_ADAPTIVE_THREADS=0";
  const long long ms = 1000000;  // ns
  long long now = clock_ns();
  EXPECT_EQ(threads_for_next_run(2, now), 2);
  // A 1 ms run of 2 threads whose waits exceed its wall time (their work summed is less than
  // one wall time): alone for the next 8 ms.
  record_team_run(2, ms, 3 * ms / 2, now);
  EXPECT_EQ(threads_for_next_run(2, now + 7 * ms), 1);
  EXPECT_EQ(threads_for_next_run(2, now + 9 * ms), 2);
  // Lost again: the back-off doubles (16 ms alone).
  now += 9 * ms;
  record_team_run(2, ms, 3 * ms / 2, now);
  EXPECT_EQ(threads_for_next_run(2, now + 15 * ms), 1);
  EXPECT_EQ(threads_for_next_run(2, now + 17 * ms), 2);
  // A won run (little waiting) resets it; a run with no barrier says nothing.
  now += 17 * ms;
  record_team_run(2, ms, ms / 10, now);
  record_team_run(2, ms, 0, now);
  EXPECT_EQ(threads_for_next_run(2, now + 1), 2);
  record_team_run(2, ms, 3 * ms / 2, now);
  EXPECT_EQ(threads_for_next_run(2, now + 7 * ms), 1);
  EXPECT_EQ(threads_for_next_run(2, now + 9 * ms), 2);
  EXPECT_EQ(threads_for_next_run(1, now), 1);
  // Three threads lose only if the waits exceed twice the wall time.
  now += 9 * ms;
  record_team_run(3, ms, 3 * ms / 2, now);
  EXPECT_EQ(threads_for_next_run(3, now + 1), 3);
}
