#include "softsim/dynamics/stable_step.hpp"

#include <sstream>

#include "softsim/io/errors.hpp"
#include "softsim/mesh/quality.hpp"

namespace softsim::dynamics {

CriticalStep critical_time_step(const mesh::TetMesh& mesh, const material::ElasticParameters& p) {
  CriticalStep c;
  c.min_altitude = 1e300;
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const double h = mesh::tet_quality(mesh, e).min_altitude;
    if (h < c.min_altitude) c.min_altitude = h;
  }
  c.wave_speed = material::dilatational_wave_speed(p);
  c.dt = c.min_altitude / c.wave_speed;  // 000 eq. 34
  return c;
}

StepChoice choose_time_step(const CriticalStep& critical, std::optional<double> requested,
                            double safety_factor, bool force) {
  StepChoice s;
  if (requested) {
    if (!(*requested > 0)) throw InputError("solver: the time step must be positive");
    s.dt = *requested;
    if (s.dt > critical.dt) {
      if (!force) {
        std::ostringstream msg;
        msg << "requested time step " << s.dt << " s exceeds the critical step " << critical.dt
            << " s (000 eq. 34: smallest altitude " << critical.min_altitude << " m / wave speed "
            << critical.wave_speed << " m/s); set solver.force_dt to run it anyway";
        throw ConfigInputError("/solver", msg.str());
      }
      s.forced = true;
    }
    return s;
  }
  if (!(safety_factor > 0 && safety_factor <= 1.0))
    throw InputError("solver: the safety factor must lie in (0, 1]");
  s.dt = safety_factor * critical.dt;
  return s;
}

}  // namespace softsim::dynamics
