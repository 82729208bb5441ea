#pragma once
// The explicit step limit Δt_cr = L_e / c (000 eq. 34) with L_e the smallest element altitude
// (3V / largest face area) and c the longitudinal wave speed (000 eq. 35), and the choice of
// the step actually used.
#include <optional>

#include "softsim/material/elastic.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::dynamics {

struct CriticalStep {
  double min_altitude = 0;  // L_e (m)
  double wave_speed = 0;    // c (m/s)
  double dt = 0;            // Δt_cr (s)
};

CriticalStep critical_time_step(const mesh::TetMesh& mesh, const material::ElasticParameters& p);

struct StepChoice {
  double dt = 0;
  bool forced = false;  // a requested step above Δt_cr that the user forced
};

// With a requested step: accepted if dt ≤ Δt_cr, otherwise InputError unless `force`.
// Without one: safety_factor × Δt_cr (0 < safety_factor ≤ 1, else InputError).
StepChoice choose_time_step(const CriticalStep& critical, std::optional<double> requested,
                            double safety_factor, bool force);

}  // namespace softsim::dynamics
