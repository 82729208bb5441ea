#pragma once
// What a law with more than F needs per element in the explicit kernels (material/
// hyperelastic.hpp): a fibre direction per element slot, and internal variables per slot that
// a step advances. ElementSet owns the arrays; a law without them gets none of this (no array,
// no read, the kernels of before).
//
// Internal variables are double-buffered by step parity: step n reads buffer n mod 2 (the state
// after step n − 1) and writes buffer (n + 1) mod 2, so a step's threads never read a slot
// another thread writes, and computing the forces of step n again (the start-up acceleration,
// the reactions) rewrites the same values instead of advancing the state twice.
namespace softsim::fem {

// Which step an element phase belongs to and its size (0: the state does not move).
struct StepClock {
  int step = 0;
  double dt = 0;
};

namespace kernels {

struct LawData {
  const double* fibre[3] = {nullptr, nullptr, nullptr};  // per slot, component-major; null: the law's own
  const double* state_in = nullptr;                      // component c of slot k at [c * stride + k]
  double* state_out = nullptr;
  int stride = 0;
  double dt = 0;
};

}  // namespace kernels
}  // namespace softsim::fem
