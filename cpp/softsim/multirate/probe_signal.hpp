#pragma once
// Probe trajectories of the 001 §6 experiments, as a displacement (m) of the haptic probe
// from the contact node's rest position along the probe direction.
namespace softsim::multirate {

struct ProbeSignal {
  enum class Kind {
    kChirp,        // A sin(2 pi (f0 t + (f1 - f0) t^2 / (2 T))): constant amplitude, frequency rising linearly
    kStep,         // 0 before start_time, A after
    kRampHold,     // 0 before start_time, rising linearly to A over ramp_time, then held
    kGrowingSine,  // A min(t / T, 1) sin(2 pi f0 t): constant frequency, amplitude growing (001 Fig. 8)
  };
  Kind kind = Kind::kChirp;
  double amplitude = 1e-3;       // A (m)
  double start_frequency = 0.0;  // f0 (Hz)
  double end_frequency = 10.0;   // f1 (Hz), chirp only
  double sweep_time = 10.0;      // T (s): chirp sweep time / growing-sine growth time
  double start_time = 0.0;       // s, step and ramp
  double ramp_time = 1.0;        // s, ramp

  double position(double t) const;
  // Instantaneous frequency (Hz) of the periodic inputs; 0 for step and ramp.
  double frequency(double t) const;
};

}  // namespace softsim::multirate
