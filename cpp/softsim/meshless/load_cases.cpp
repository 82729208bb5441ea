#include "softsim/meshless/load_cases.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

namespace softsim::meshless {

std::string dataset_kind_name(DatasetKind k) {
  switch (k) {
    case DatasetKind::axis_x: return "axis_x";
    case DatasetKind::axis_y: return "axis_y";
    case DatasetKind::axis_z: return "axis_z";
    case DatasetKind::random: return "random";
    case DatasetKind::check: return "check";
  }
  return "?";
}

std::vector<Eigen::Vector3d> dataset_forces(const DatasetSpec& spec) {
  std::vector<Eigen::Vector3d> f;
  switch (spec.kind) {
    case DatasetKind::axis_x:
    case DatasetKind::axis_y:
    case DatasetKind::axis_z: {
      const int axis = spec.kind == DatasetKind::axis_x ? 0 : spec.kind == DatasetKind::axis_y ? 1 : 2;
      std::vector<double> mags = spec.magnitudes;
      if (mags.empty()) {
        if (spec.count < 1) throw std::invalid_argument("dataset_forces: count must be >= 1");
        for (int k = 1; k <= spec.count; ++k) mags.push_back(spec.max_force * k / spec.count);
      }
      for (double m : mags) f.push_back(m * Eigen::Vector3d::Unit(axis));
      break;
    }
    case DatasetKind::random: {
      if (spec.count < 1) throw std::invalid_argument("dataset_forces: count must be >= 1");
      std::mt19937_64 engine(spec.seed);
      const auto uniform = [&] { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };
      const double two_pi = 2.0 * std::acos(-1.0);
      for (int c = 0; c < spec.count; ++c) {
        const double magnitude = spec.max_force * uniform();
        const double cos_theta = 2.0 * uniform() - 1.0;
        const double phi = two_pi * uniform();
        const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
        f.push_back(magnitude * Eigen::Vector3d(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
      }
      break;
    }
    case DatasetKind::check: f.push_back(spec.force); break;
  }
  return f;
}

}  // namespace softsim::meshless
