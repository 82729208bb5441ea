#include "softsim/dynamics/stable_step.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

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

DeformedCriticalStep::DeformedCriticalStep(const mesh::TetMesh& mesh, std::vector<char> follows,
                                           const material::ElasticParameters& p)
    : mesh_(&mesh), wave_speed_(material::dilatational_wave_speed(p)) {
  if (static_cast<int>(follows.size()) != mesh.num_tets())
    throw std::invalid_argument("DeformedCriticalStep: one flag per tetrahedron");
  for (int e = 0; e < mesh.num_tets(); ++e) {
    if (follows[e]) deforming_.push_back(e);
    else fixed_altitude_ = std::min(fixed_altitude_, mesh::tet_quality(mesh, e).min_altitude);
  }
}

void DeformedCriticalStep::remove(const std::vector<int>& elements) {
  std::vector<int> gone(elements);
  std::sort(gone.begin(), gone.end());
  deforming_.erase(std::remove_if(deforming_.begin(), deforming_.end(),
                                  [&](int e) { return std::binary_search(gone.begin(), gone.end(), e); }),
                   deforming_.end());
}

CriticalStep DeformedCriticalStep::at(const double* u) const {
  CriticalStep c;
  c.min_altitude = fixed_altitude_;
  const auto& nodes = mesh_->nodes;
  for (int e : deforming_) {
    const auto& t = mesh_->tets[e];
    Eigen::Vector3d x[4];
    for (int a = 0; a < 4; ++a) x[a] = nodes[t[a]] + Eigen::Vector3d(u[3 * t[a]], u[3 * t[a] + 1], u[3 * t[a] + 2]);
    const double six_v = (x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0]));
    // Largest face area (twice it), over the four faces.
    double max_twice_area = 0;
    for (int a = 0; a < 4; ++a) {
      const Eigen::Vector3d& p = x[(a + 1) % 4];
      const Eigen::Vector3d& q = x[(a + 2) % 4];
      const Eigen::Vector3d& r = x[(a + 3) % 4];
      max_twice_area = std::max(max_twice_area, (q - p).cross(r - p).norm());
    }
    // 3V / A = (6V) / (2A); an inverted or flat element has no positive altitude.
    const double h = six_v > 0 && max_twice_area > 0 ? six_v / max_twice_area : 0.0;
    c.min_altitude = std::min(c.min_altitude, h);
  }
  c.wave_speed = wave_speed_;
  c.dt = c.min_altitude / c.wave_speed;  // 000 eq. 34
  return c;
}

StepChoice choose_time_step(const CriticalStep& critical, std::optional<double> requested,
                            double safety_factor, bool force) {
  StepChoice s;
  if (requested) {
    if (!(*requested > 0)) throw ConfigInputError("/solver/dt", "expected a positive time step");
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
