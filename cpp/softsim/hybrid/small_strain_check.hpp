#pragma once
// The condition under which DHD-FEA's cheap elements are valid: "the deformation of linear
// finite elements is constrained to less than 10 %, enabling the use of the initial (reference)
// configuration to approximate the deformed geometry" (000 §2.2.2). A run records the largest
// deformation any small-strain element reached, where and when, and says when the limit was
// broken (a warning: the run goes on, its error in that region is the partition's to answer).
// Measures, per kind, of what the kind gets wrong:
//   * linear: ‖∇u‖₂, the largest singular value of F − I (strain and rotation: a small-strain
//     element is wrong under either);
//   * corotational: the largest |principal value| of E = (FᵀF − I)/2 (the rotation is handled,
//     the strain is still taken as small).
#include <vector>

#include "softsim/fem/element_kind.hpp"
#include "softsim/fem/tet_geometry.hpp"
#include "softsim/hybrid/element_strain.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::hybrid {

inline constexpr double kSmallStrainLimit = 0.10;  // 000 §2.2.2

struct SmallStrainRecord {
  int elements = 0;      // small-strain elements watched
  double largest = 0;    // the largest measure seen
  int element = -1;      // where (−1: none watched or all undeformed)
  double time = 0;       // when (s)
  int samples = 0;       // states looked at
  bool broken() const { return largest > kSmallStrainLimit; }
};

// The measure a kind's validity is judged by (see the top of this file).
StrainMeasure small_strain_measure(fem::ElementKind kind);

class SmallStrainCheck {
 public:
  // Watches the elements whose kind is flagged small_strain (fem::kElementKinds).
  SmallStrainCheck(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds);
  // Looks at the state u (3 per node) at `time`; `skip(e)` leaves out a removed element. No
  // allocation: a run calls this between chunks of steps.
  template <class Skip>
  void observe(const double* u, double time, const Skip& skip) {
    ++record_.samples;
    for (std::size_t i = 0; i < elements_.size(); ++i) {
      const int e = elements_[i];
      if (skip(e)) continue;
      const Eigen::Matrix3d F = fem::deformation_gradient(shapes_[i], fem::corner_displacements(*mesh_, e, u));
      // The Frobenius norm bounds both measures from above (‖A‖₂ ≤ ‖A‖_F): most elements are
      // passed over without the eigenvalue solve.
      const Eigen::Matrix3d H = F - Eigen::Matrix3d::Identity();
      const double bound = measures_[i] == StrainMeasure::displacement_gradient
                               ? H.norm()
                               : (0.5 * (H + H.transpose() + H.transpose() * H)).norm();
      if (!(bound > record_.largest)) continue;
      const double s = strain_of(F, measures_[i]);
      if (s > record_.largest) {
        record_.largest = s;
        record_.element = e;
        record_.time = time;
      }
    }
  }
  void observe(const double* u, double time) {
    observe(u, time, [](int) { return false; });
  }
  const SmallStrainRecord& record() const { return record_; }

 private:
  const mesh::TetMesh* mesh_;
  std::vector<int> elements_;
  std::vector<fem::TetShape> shapes_;
  std::vector<StrainMeasure> measures_;
  SmallStrainRecord record_;
};

}  // namespace softsim::hybrid
