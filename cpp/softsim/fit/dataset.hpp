#pragma once
// The data the fits learn from: load cases on one body, each a force at the loaded node and the
// displacement of every surface node (002 §3: "the displacement of all nodes corresponding to a
// given spatial force was calculated by global meshless method in advance").
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

namespace softsim::fit {

struct LoadCase {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N
  Eigen::MatrixXd displacement;                     // nodes × 3, m
};

struct Dataset {
  std::string source;  // where it came from (path), for messages
  std::string kind;    // "axis_x", "axis_y", "axis_z", "random", "check", ...
  int loaded_node = 0;    // 0-based row of `nodes`
  Eigen::MatrixXd nodes;  // nodes × 3, m (the surface the fits describe)
  std::vector<LoadCase> cases;
  // Response to unit forces along x, y, z (column d), row 3*node + component. Present for a
  // linear model: then any load case is their superposition.
  std::optional<Eigen::MatrixXd> unit_solutions;
  nlohmann::json timing;  // the producer's timing block, passed through (null when absent)

  int node_count() const { return static_cast<int>(nodes.rows()); }
  int case_count() const { return static_cast<int>(cases.size()); }
};

// Displacement component `component` of the loaded node in every case (the paper's Δs_c).
std::vector<double> loaded_displacements(const Dataset& data, int component);

// Force component `direction` of every case.
std::vector<double> force_components(const Dataset& data, int direction);

// Largest |force component off `direction`| relative to the largest |force| of the dataset
// (0 for a dataset whose every force is along `direction`).
double off_axis_fraction(const Dataset& data, int direction);

// Whether two node lists are the same surface: the same number of nodes, each within 1e-9 of the
// surface's extent of its counterpart (node coordinates written and read back as JSON numbers
// agree far better; different meshes differ far more). The one test for every place that pairs
// datasets or a dataset with a fitted model.
bool same_surface(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

}  // namespace softsim::fit
