// Geometry of the rigid tools (scene.hpp): signed distance and outward normal, bounding box.
#include <algorithm>

#include "softsim/dynamics/scene.hpp"

namespace softsim::dynamics {

namespace {

// Distance from x to a point core q (sphere centre, nearest point of a capsule's segment) less
// the radius; the normal points from q to x (any unit vector when x sits on q).
double round_distance(const Eigen::Vector3d& x, const Eigen::Vector3d& q, double radius, Eigen::Vector3d& normal) {
  const Eigen::Vector3d d = x - q;
  const double r = d.norm();
  normal = r > 0 ? Eigen::Vector3d(d / r) : Eigen::Vector3d::UnitZ();
  return r - radius;
}

}  // namespace

double RigidTool::signed_distance(const Eigen::Vector3d& x, const Eigen::Vector3d& c, Eigen::Vector3d& n) const {
  switch (shape) {
    case Shape::sphere:
      return round_distance(x, c, radius, n);
    case Shape::capsule: {
      const double h2 = half_axis.squaredNorm();
      const double s = h2 > 0 ? std::clamp((x - c).dot(half_axis) / h2, -1.0, 1.0) : 0.0;
      return round_distance(x, c + s * half_axis, radius, n);
    }
    case Shape::plane:
      n = normal;
      return (x - c).dot(normal);
    case Shape::mesh:
      return surface->signed_distance(x - c, n);
  }
  return 0.0;
}

bool RigidTool::bounds(const Eigen::Vector3d& c, Eigen::Vector3d& lo, Eigen::Vector3d& hi) const {
  const Eigen::Vector3d r = Eigen::Vector3d::Constant(radius);
  switch (shape) {
    case Shape::sphere:
      lo = c - r;
      hi = c + r;
      return true;
    case Shape::capsule:
      lo = c - half_axis.cwiseAbs() - r;
      hi = c + half_axis.cwiseAbs() + r;
      return true;
    case Shape::plane:
      return false;
    case Shape::mesh:
      lo = c + surface->lower();
      hi = c + surface->upper();
      return true;
  }
  return false;
}

}  // namespace softsim::dynamics
