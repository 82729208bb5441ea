// A program outside softsim that uses it as a library (softsim::fe), the way a user's would:
// the paper's 5-tetrahedron cuboid from the mesher, then two facts of linear elasticity that
// linear tetrahedra reproduce exactly, so that only solver tolerance and round-off remain.
//   1. A rigid translation strains nothing: every element kind's internal forces vanish.
//   2. Uniaxial tension of a block on rollers: the top's reaction is E A ε, the free faces
//      contract by ν ε, and the strain energy is E ε² V / 2. The state is homogeneous, which
//      linear elements represent exactly, whatever the mesh.
// The first check also frees, here, an Eigen vector that the library allocated: with a
// mismatched Eigen alignment between the two (the library compiled with -march=native, this
// program without) that crashes.
// Exit status 0 when every check holds, 1 otherwise, naming what was measured.
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

#include <Eigen/Core>

#include "softsim/dynamics/static_solver.hpp"
#include "softsim/fem/assembly.hpp"
#include "softsim/fem/constitutive.hpp"
#include "softsim/mesh/cuboid.hpp"
#include "softsim/version.hpp"

using namespace softsim;

namespace {

// 000 §3.1: E = 5000 Pa, ν = 0.35, ρ = 1000 kg/m³.
const material::ElasticParameters kTissue{5000.0, 0.35, 1000.0};
constexpr double kL = 0.02, kH = 0.03;  // block L × L × H (m)

int failures = 0;

void check(bool ok, const char* what, double measured, double expected) {
  std::printf("%s %s: %.12g (expected %.12g)\n", ok ? "ok  " : "FAIL", what, measured, expected);
  if (!ok) ++failures;
}

dynamics::DisplacementConstraint on_set(const mesh::TetMesh& m, const char* set, int component, double value) {
  dynamics::DisplacementConstraint c;
  c.name = set;
  c.nodes = m.node_sets.at(set);
  c.components = {component == 0, component == 1, component == 2};
  c.displacement[component] = value;
  return c;
}

void rigid_translation(const mesh::TetMesh& m, const fem::Material& material) {
  const Eigen::Vector3d d(1e-3, -2e-3, 5e-4);
  std::vector<double> u(3 * m.nodes.size());
  for (int i = 0; i < m.num_nodes(); ++i)
    for (int c = 0; c < 3; ++c) u[3 * i + c] = d[c];
  // The forces of a strain of order round-off (1e-16) on elements of size h: E h |d| 1e-16 each.
  const double h = kL / 2;
  const double tolerance = 1e-12 * kTissue.youngs_modulus * h * d.norm();
  for (int k = 0; k < fem::kNumElementKinds; ++k) {
    const auto kind = static_cast<fem::ElementKind>(k);
    const fem::Assembler assembler(m, std::vector<fem::ElementKind>(m.num_tets(), kind), material);
    Eigen::VectorXd f;
    assembler.internal_forces(u.data(), f);
    const double largest = f.lpNorm<Eigen::Infinity>();
    std::printf("rigid translation, %s elements: ", fem::kind_name(kind));
    check(f.size() == 3 * m.num_nodes() && largest <= tolerance, "largest internal force (N)", largest, 0.0);
  }
}

void uniaxial_tension(const mesh::TetMesh& m, const fem::Material& material) {
  const double strain = 0.01;
  dynamics::Scene scene;
  scene.constraints = {on_set(m, "bottom", 2, 0.0), on_set(m, "x_min", 0, 0.0), on_set(m, "y_min", 1, 0.0),
                       on_set(m, "top", 2, strain * kH)};
  dynamics::StaticOptions options;
  options.increments = 1;  // linear elements: one load step is exact
  const auto r = dynamics::solve_static(m, std::vector<fem::ElementKind>(m.num_tets(), fem::ElementKind::linear),
                                        material, scene, options);
  // Exact up to the Newton tolerance (1e-9 of the force scale) and round-off.
  const double rel = 1e-8;
  const double E = kTissue.youngs_modulus, nu = kTissue.poisson_ratio;
  const double force = E * kL * kL * strain;
  check(std::abs(r.reactions[3].z() - force) <= rel * force, "uniaxial tension: top reaction E A eps (N)",
        r.reactions[3].z(), force);
  const int corner = m.num_nodes() - 1;  // (L, L, H): free in x and y
  const double lateral = -nu * strain * kL;
  for (int c = 0; c < 2; ++c)
    check(std::abs(r.displacement[3 * corner + c] - lateral) <= rel * std::abs(lateral),
          "uniaxial tension: lateral displacement of the free corner (m)", r.displacement[3 * corner + c], lateral);
  const double energy = 0.5 * E * strain * strain * kL * kL * kH;
  check(std::abs(r.strain_energy - energy) <= rel * energy, "uniaxial tension: strain energy (J)", r.strain_energy,
        energy);
}

}  // namespace

int main() {
  try {
    std::printf("softsim %s as a library\n", kVersion);
    mesh::CuboidSpec spec;
    spec.cells = {2, 2, 3};
    spec.size = Eigen::Vector3d(kL, kL, kH);
    const mesh::TetMesh m = mesh::make_cuboid(spec);
    const fem::Material material = fem::Material::make(kTissue, material::NeoHookeanForm::paper);
    rigid_translation(m, material);
    uniaxial_tension(m, material);
  } catch (const std::exception& e) {
    std::printf("FAIL %s\n", e.what());
    return 1;
  }
  std::printf("%s\n", failures ? "consumer: FAILED" : "consumer: every check holds");
  return failures ? 1 : 0;
}
