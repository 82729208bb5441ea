#pragma once
// The two diagnostic studies of rpim_precompute besides the datasets:
//   stability    vary one RPIM parameter at a time around a base setting on the plate and record
//                conditioning, consistency and the loaded-node compliance, or the numerical
//                failure (singular moment matrix, singular K) with its message;
//   convergence  refine the nodes of a block with a manufactured solution and record the error.
#include <string>
#include <vector>

#include "softsim/meshless/manufactured.hpp"
#include "softsim/meshless/plate_dataset.hpp"

namespace softsim::meshless {

enum class StabilityParameter { q, alpha_c, d_c_spacing_factor, support_spacing_factor, nearest_count };
inline constexpr StabilityParameter kStabilityParameters[] = {
    StabilityParameter::q, StabilityParameter::alpha_c, StabilityParameter::d_c_spacing_factor,
    StabilityParameter::support_spacing_factor, StabilityParameter::nearest_count};
// The parameter's name, also its key in the stability config.
std::string stability_parameter_name(StabilityParameter p);

struct StabilityPoint {
  StabilityParameter parameter = StabilityParameter::q;
  double value = 0;
  bool ok = false;
  std::string message;          // the NumericalError text when !ok
  Eigen::Vector3d compliance = Eigen::Vector3d::Zero();  // u_a / F_a at the loaded node (m/N)
  PlateConditioning conditioning;
  RbfParams rbf;
  SupportRule support;
};

StabilityPoint stability_point(const PlateScene& scene, RpimSettings settings, StabilityParameter parameter,
                               double value);

struct ConvergencePoint {
  int nodes_per_edge = 0;
  BlockStudyResult result;
};

// cells_per_edge = nodes_per_edge - 1 (one background cell per nodal interval).
std::vector<ConvergencePoint> convergence_study(const BlockStudy& block, const RpimSettings& settings,
                                                const std::vector<int>& nodes_per_edge);
// Least-squares slope of log(error) against log(h).
double observed_rate(const std::vector<double>& spacing, const std::vector<double>& error);

}  // namespace softsim::meshless
