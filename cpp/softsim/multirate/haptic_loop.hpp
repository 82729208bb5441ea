#pragma once
// The haptic loop of 001 §3 at the haptic rate (1 kHz): every frame
//   1. read the probe position p (a displacement along the probe direction e),
//   2. the spring between probe and contact node gives the model's input
//      f = k_s (p e - u_c),
//   3. advance the model one frame with f held constant,
//   4. send back the force of the same spring at the updated contact position,
//      F = e . k_s (p e - u_c+)   (the haptic output, recorded).
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "softsim/multirate/frame_stepper.hpp"
#include "softsim/multirate/probe_signal.hpp"

namespace softsim::multirate {

struct HapticLoopSpec {
  double frame_step = 1e-3;       // s
  long frames = 10000;
  double probe_stiffness = 10.0;  // k_s (N/m)
  Eigen::VectorXd direction;      // unit probe direction, one entry per DOF of the contact node
  // The loop is declared unstable (NumericalError) when the contact displacement exceeds this
  // multiple of the probe amplitude: a passive model pulled by a spring cannot get there.
  double blow_up_factor = 1e3;
  // Called every kProgressFrames frames and after the last with the frames done so far in this
  // loop and the simulated time (a progress line for long runs); empty: never.
  std::function<void(long, double)> progress;
};

inline constexpr long kProgressFrames = 4096;

struct LoopRecord {
  std::vector<double> probe;          // p at each frame (m)
  std::vector<double> force;          // F sent to the device (N)
  std::vector<double> contact;        // contact displacement along e after the frame (m)
  std::vector<int> primary_nodes;     // nodes solved at the haptic rate in the frame
};

// Runs `spec.frames` frames from the stepper's current state (call reset() first for a fresh
// run). Writes into `record`, resized once before the loop. Throws NumericalError when the
// loop diverges.
void run_haptic_loop(FrameStepper& stepper, const ProbeSignal& signal, const HapticLoopSpec& spec, LoopRecord& record);

}  // namespace softsim::multirate
