#pragma once
// What an async_sim run will need, estimated from its config before anything is allocated, so
// that a long series or a dense model beyond the machine is refused (exit 2, naming the member
// that sets the size) instead of ending in std::bad_alloc hours into the run; and how much work
// it asks for, refused beyond io::max_element_updates() like a dhd_sim step count.
#include <string>
#include <vector>

#include "softsim/multirate/run_config.hpp"

namespace softsim::multirate {

// One share of the estimate: the config member that sets its size and what takes the memory.
struct MemoryShare {
  std::string pointer;  // JSON pointer of the member, e.g. "/haptics/duration"
  std::string what;     // e.g. "the per-frame records of 3 loops"
  double bytes = 0.0;
};

// The shares of a run's memory (records per frame, time series, frequency bins, dense
// factorisations, the exact reference), each an upper estimate; the sum is the run's.
std::vector<MemoryShare> estimate_run_memory(const RunConfig& config);

// Element updates the run asks for: every timed loop updates each bar element once a frame
// (the whole model, and the regions at most as often), and a frame of the exact reference is a
// dense product of order (2n)^2, counted as (2n)^2 / 32 element updates (a multiply-add against
// the about 32 of a 1-D element update with its solve).
double estimate_run_work(const RunConfig& config);

// Refuses (ConfigInputError at the largest share's member, which run_app reports with the config
// file) a run whose memory estimate exceeds io::memory_limit_bytes() or whose work exceeds
// io::max_element_updates() (at /haptics/duration).
void require_run_resources(const RunConfig& config);

}  // namespace softsim::multirate
