#pragma once
// Thin OpenMP helpers of the explicit engine: run a body on N threads (inline without OpenMP)
// and an orphaned barrier.
#if defined(SOFTSIM_HAVE_OPENMP)
#include <omp.h>
#endif

namespace softsim::dynamics::detail {

// Runs body(thread, threads) on `threads` OpenMP threads (or inline without OpenMP).
template <class Body>
void parallel(int threads, Body&& body) {
#if defined(SOFTSIM_HAVE_OPENMP)
  if (threads > 1) {
#pragma omp parallel num_threads(threads)
    body(omp_get_thread_num(), omp_get_num_threads());
    return;
  }
#endif
  body(0, 1);
}

inline void barrier() {
#if defined(SOFTSIM_HAVE_OPENMP)
#pragma omp barrier
#endif
}

}  // namespace softsim::dynamics::detail
