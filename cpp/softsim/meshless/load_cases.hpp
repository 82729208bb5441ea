#pragma once
// The force sets of 002 §4.2 applied at the loaded node:
//   axis_x / axis_y / axis_z   n forces of increasing magnitude along one axis (§4.2.1, §5.1.1:
//                              0.2, 0.4, ..., 1.0 N for n = 5)
//   random                     forces of random magnitude (0–max) and direction (§4.2.2: 100)
//   check                      one given force (§5.2: (0.9, -0.7, -0.22) N)
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace softsim::meshless {

enum class DatasetKind { axis_x, axis_y, axis_z, random, check };
std::string dataset_kind_name(DatasetKind k);

struct DatasetSpec {
  DatasetKind kind = DatasetKind::axis_z;
  int count = 5;                  // axis_*: magnitudes k max/count, k = 1..count; random: cases
  static constexpr int kRandomCount = 100;  // random: the count when none is given
  double max_force = 1.0;         // N
  std::vector<double> magnitudes; // axis_*: explicit magnitudes (N) instead of count
  std::uint64_t seed = 2017;      // random
  Eigen::Vector3d force{0.9, -0.7, -0.22};  // check (N)
};

// The forces of a dataset. The random set is a pure function of the seed: a std::mt19937_64
// engine seeded with `seed` gives 64-bit words w, mapped to u = (w >> 11) 2⁻⁵³ in [0, 1);
// each case takes three: |F| = max u₁, cos θ = 2 u₂ - 1, φ = 2π u₃ (uniform on the sphere).
std::vector<Eigen::Vector3d> dataset_forces(const DatasetSpec& spec);

}  // namespace softsim::meshless
