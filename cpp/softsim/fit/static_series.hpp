#pragma once
// A dataset built from static solutions of a body under increasing loads (dhd_sim "dhd_result"
// artifacts on one "tet_mesh"): the nonlinear counterpart of the RPIM datasets. Each case is one
// static solution; its force is stated in the config (the load the solution was computed for),
// the surface is a node set of the mesh (default "top", the face the fits describe) ordered by
// (y, x), and the loaded node is the surface node nearest a given point.
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "softsim/fit/dataset.hpp"
#include "softsim/io/json_reader.hpp"

namespace softsim::fit {

struct StaticCase {
  std::string result;  // path of a dhd_result artifact
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N, the load of that solution
};

struct StaticSeries {
  std::string mesh;  // path of the tet_mesh artifact the solutions were computed on
  std::string surface_set = "top";
  Eigen::Vector3d loaded_point = Eigen::Vector3d::Zero();
  std::vector<StaticCase> cases;
};

// {"kind": "static_series", "mesh": ..., "surface_set": "top", "loaded_point": [x, y, z],
//  "cases": [{"result": ..., "force": [fx, fy, fz]}, ...]}
StaticSeries static_series_from_json(const io::JsonReader& node);

// Reads the mesh and every result (through io). Throws InputError for a missing node set, a
// result whose size does not match the mesh, or a bad artifact.
Dataset read_static_series(const StaticSeries& spec);

}  // namespace softsim::fit
