#pragma once
// Dual-mode partitioning (000 §2.2.1): which elements are nonlinear (TLED or ANP, the operational
// region) and which are linear (or corotational, in place of linear). Every strategy first
// decides the operational set, then assigns kinds.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/fem/element_kind.hpp"
#include "softsim/hybrid/element_strain.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::hybrid {

enum class PartitionKind { uniform, layers, linear_fraction, tags, sphere, strain };
enum class DistanceMetric { euclidean, depth };

struct PartitionSpec {
  PartitionKind kind = PartitionKind::uniform;
  fem::ElementKind uniform_element = fem::ElementKind::tled;  // uniform
  fem::ElementKind linear_element = fem::ElementKind::linear;  // what non-operational elements become
  fem::ElementKind nonlinear_element = fem::ElementKind::tled;  // what operational elements become (tled, anp)
  // layers
  int nonlinear_layers = 0;
  std::string tag = "layer";
  // linear_fraction (also strain with a fraction)
  double linear_fraction = 0;
  std::optional<Eigen::Vector3d> operating_point;  // default: centre of the bounding box's top face
  DistanceMetric distance = DistanceMetric::euclidean;
  // tags
  std::vector<int> nonlinear_values;
  // sphere
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0;
  // strain
  std::vector<double> reference_displacement;
  StrainMeasure measure = StrainMeasure::displacement_gradient;
  std::optional<double> threshold;  // else linear_fraction
};

// One kind per element. Throws InputError for a spec the mesh cannot satisfy (missing tag,
// wrong reference size, fraction outside [0, 1]).
std::vector<fem::ElementKind> make_partition(const mesh::TetMesh& mesh, const PartitionSpec& spec);

// Building blocks.
Eigen::Vector3d default_operating_point(const mesh::TetMesh& mesh);
std::vector<Eigen::Vector3d> element_centroids(const mesh::TetMesh& mesh);

}  // namespace softsim::hybrid
