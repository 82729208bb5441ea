#pragma once
// The explicit step limit Δt_cr = L_e / c (000 eq. 34) with L_e the smallest element altitude
// (3V / largest face area) and c the longitudinal wave speed (000 eq. 35), and the choice of
// the step actually used.
#include <optional>
#include <vector>

#include "softsim/material/elastic.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::dynamics {

struct CriticalStep {
  double min_altitude = 0;  // L_e (m)
  double wave_speed = 0;    // c (m/s)
  double dt = 0;            // Δt_cr (s)
};

CriticalStep critical_time_step(const mesh::TetMesh& mesh, const material::ElasticParameters& p);

// 000 eq. 34 on the deformed mesh, for re-estimating the step during a run: the smallest
// altitude of the current geometry X + u over the elements whose stiffness follows the
// deformation (TLED and ANP: `follows[e]` true) and the smallest reference altitude over the
// others (small-strain and corotational elements keep their reference stiffness, and with it
// their reference limit), over the reference wave speed c (000 eq. 35). An element flattened by
// the deformation shortens the step in proportion; an inverted one gives a limit of zero.
class DeformedCriticalStep {
 public:
  DeformedCriticalStep(const mesh::TetMesh& mesh, std::vector<char> follows, const material::ElasticParameters& p);
  // Δt_cr at displacement `u` (3 per node); `min_altitude` and `wave_speed` as in CriticalStep.
  CriticalStep at(const double* u) const;
  // Elements a cut removed no longer count (their geometry may go anywhere). The reference
  // altitude of removed small-strain elements stays in the minimum: conservative.
  void remove(const std::vector<int>& elements);

 private:
  const mesh::TetMesh* mesh_;
  std::vector<int> deforming_;  // elements whose altitude is re-measured
  double fixed_altitude_ = 1e300;  // smallest reference altitude of the others
  double wave_speed_ = 0;
};

struct StepChoice {
  double dt = 0;
  bool forced = false;  // a requested step above Δt_cr that the user forced
};

// With a requested step: accepted if dt ≤ Δt_cr, otherwise InputError unless `force`.
// Without one: safety_factor × Δt_cr (0 < safety_factor ≤ 1, else InputError).
StepChoice choose_time_step(const CriticalStep& critical, std::optional<double> requested,
                            double safety_factor, bool force);

}  // namespace softsim::dynamics
