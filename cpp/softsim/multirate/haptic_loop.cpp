#include "softsim/multirate/haptic_loop.hpp"

#include <cmath>
#include <sstream>

#include "softsim/io/errors.hpp"

namespace softsim::multirate {

void run_haptic_loop(FrameStepper& stepper, const ProbeSignal& signal, const HapticLoopSpec& spec, LoopRecord& record) {
  const int p = stepper.dofs_per_node();
  if (spec.direction.size() != p) throw InputError("haptic loop: the probe direction needs one entry per DOF of the contact node");
  if (!(spec.probe_stiffness > 0)) throw InputError("haptic loop: the probe stiffness must be positive");
  if (!(spec.direction.norm() > 0)) throw InputError("haptic loop: the probe direction must not be zero");
  const Eigen::VectorXd e = spec.direction.normalized();
  const std::size_t frames = static_cast<std::size_t>(spec.frames);
  record.probe.assign(frames, 0.0);
  record.force.assign(frames, 0.0);
  record.contact.assign(frames, 0.0);
  record.primary_nodes.assign(frames, 0);
  const double limit = spec.blow_up_factor * std::abs(signal.amplitude);
  Eigen::VectorXd force(p);
  for (std::size_t n = 0; n < frames; ++n) {
    const double probe = signal.position(static_cast<double>(n) * spec.frame_step);
    for (int d = 0; d < p; ++d) force[d] = spec.probe_stiffness * (probe * e[d] - stepper.contact_displacement(d));
    stepper.advance(force);
    double out = 0.0, along = 0.0;
    for (int d = 0; d < p; ++d) {
      const double u = stepper.contact_displacement(d);
      out += e[d] * spec.probe_stiffness * (probe * e[d] - u);
      along += e[d] * u;
    }
    if (!std::isfinite(out) || std::abs(along) > limit) {
      std::ostringstream msg;
      msg << "haptic loop: frame " << n + 1 << ": contact displacement " << along << " m exceeds " << spec.blow_up_factor
          << " x the probe amplitude " << signal.amplitude << " m (the coupled loop with probe stiffness "
          << spec.probe_stiffness << " N/m is unstable)";
      throw NumericalError(msg.str());
    }
    record.probe[n] = probe;
    record.force[n] = out;
    record.contact[n] = along;
    record.primary_nodes[n] = stepper.primary_nodes();
    if (spec.progress && ((n + 1) % kProgressFrames == 0 || n + 1 == frames))
      spec.progress(static_cast<long>(n + 1), static_cast<double>(n + 1) * spec.frame_step);
  }
}

}  // namespace softsim::multirate
