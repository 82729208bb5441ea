// RPIM on a tetrahedral domain (the organ scene of 002 §5.3): the tetrahedral Gauss rules, the
// shape functions' linear consistency, K's symmetry and rigid-body modes, a patch test and
// agreement with the linear tetrahedral FEM on the same mesh under the same load.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "softsim/dynamics/static_solver.hpp"
#include "softsim/fem/constitutive.hpp"
#include "softsim/fem/element_kind.hpp"
#include "softsim/mesh/cuboid.hpp"
#include "softsim/meshless/assembly.hpp"
#include "softsim/meshless/conditioning.hpp"
#include "softsim/meshless/shape_table.hpp"
#include "softsim/meshless/organ_scene.hpp"
#include "softsim/meshless/rpim_model.hpp"
#include "softsim/meshless/tet_quadrature.hpp"

using namespace softsim;
using namespace softsim::meshless;

namespace {

// A box of nx × ny × nz cells, five tets each, whose interior nodes are moved by up to 0.15 of
// a cell in every direction (a fixed pseudo-random pattern): an unstructured tetrahedral domain
// with the box's flat faces, so that a linear field is easy to impose on its surface.
mesh::TetMesh jittered_box(int nx, int ny, int nz, const Eigen::Vector3d& size) {
  mesh::CuboidSpec spec;
  spec.cells = {nx, ny, nz};
  spec.size = size;
  mesh::TetMesh m = mesh::make_cuboid(spec);
  const Eigen::Vector3d h(size.x() / nx, size.y() / ny, size.z() / nz);
  std::vector<char> on_surface(m.nodes.size(), 0);
  for (int n : m.node_sets.at("boundary")) on_surface[n] = 1;
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    if (on_surface[i]) continue;
    const double k = static_cast<double>(i);
    const Eigen::Vector3d r(std::sin(12.9898 * k + 1.0), std::sin(78.233 * k + 2.0), std::sin(37.719 * k + 3.0));
    m.nodes[i] += 0.15 * r.cwiseProduct(h);
  }
  for (const auto& t : m.tets) EXPECT_GT(mesh::signed_volume(m, t), 0.0);
  return m;
}

RpimSettings linear_settings() {
  RpimSettings s;
  s.polynomial = PolynomialBasis::linear;
  s.d_c = {LengthSpec::Kind::spacing_factor, 1.0};
  s.support_radius = {LengthSpec::Kind::spacing_factor, 2.5};
  return s;
}

MeshlessProblem box_problem(const mesh::TetMesh& m, int rule, double youngs, double poisson) {
  OrganScene scene;
  scene.tet_rule = rule;
  scene.youngs_modulus = youngs;
  scene.poisson_ratio = poisson;
  scene.fixed_sets = {};
  return organ_problem(scene, m);
}

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// Shape functions and K of an unsupported scene (no factorisation: K is singular without supports).
struct Unsupported {
  std::vector<Eigen::Vector3d> nodes;
  double spacing = 0;
  ShapeTable shapes;
  SparseMatrix k;
};
Unsupported unsupported(const mesh::TetMesh& m) {
  const MeshlessProblem p = box_problem(m, 4, 5000, 0.35);
  const RpimSettings s = linear_settings();
  Unsupported u;
  u.nodes = p.nodes;
  u.spacing = p.mean_spacing;
  u.shapes = build_shape_table(p.nodes, p.quadrature, resolve_support(s, u.spacing), resolve_rbf(s, u.spacing));
  u.k = assemble_stiffness(u.shapes, static_cast<int>(p.nodes.size()), lame_from_young(5000, 0.35));
  return u;
}

}  // namespace

// ∫ x^a y^b z^c over the unit tetrahedron is a! b! c! / (a + b + c + 3)!; a rule of degree d
// integrates every monomial with a + b + c ≤ d exactly, and fails for some monomial of degree d + 1.
TEST(TetRule, ExactUpToItsDegreeAndNoFurther) {
  mesh::TetMesh unit;
  unit.nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  unit.tets = {{0, 1, 2, 3}};
  for (int points : {1, 4, 5}) {
    const TetRule rule = tet_rule(points);
    const QuadraturePoints q = tet_quadrature(unit, rule);
    double worst_beyond = 0;
    for (int a = 0; a <= rule.degree + 1; ++a)
      for (int b = 0; a + b <= rule.degree + 1; ++b)
        for (int c = 0; a + b + c <= rule.degree + 1; ++c) {
          double sum = 0;
          for (std::size_t g = 0; g < q.points.size(); ++g)
            sum += q.weights[g] * std::pow(q.points[g].x(), a) * std::pow(q.points[g].y(), b) *
                   std::pow(q.points[g].z(), c);
          const double exact = factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3);
          if (a + b + c <= rule.degree) EXPECT_NEAR(sum, exact, 1e-15) << points << " points, " << a << b << c;
          else worst_beyond = std::max(worst_beyond, std::abs(sum - exact) / exact);
        }
    EXPECT_GT(worst_beyond, 1e-3) << points << " points: exact beyond its degree?";
  }
  EXPECT_THROW(tet_rule(3), std::invalid_argument);
}

TEST(TetRule, WeightsSumToTheMeshVolume) {
  const mesh::TetMesh m = jittered_box(3, 2, 2, {0.03, 0.02, 0.02});
  for (int points : {1, 4, 5}) {
    const QuadraturePoints q = tet_quadrature(m, tet_rule(points));
    double sum = 0;
    for (double w : q.weights) sum += w;
    EXPECT_NEAR(sum, 0.03 * 0.02 * 0.02, 1e-18) << points;
    EXPECT_EQ(q.points.size(), m.tets.size() * static_cast<std::size_t>(points));
  }
}

// With the linear polynomial (002 eq. 11, m = 4) the shape functions reproduce 1, x, y, z and
// their gradients at every tetrahedral Gauss point: the consistency the patch test rests on.
TEST(OrganScene, ShapeFunctionsReproduceLinearFieldsAtEveryGaussPoint) {
  const mesh::TetMesh m = jittered_box(4, 3, 3, {0.04, 0.03, 0.03});
  const Unsupported u = unsupported(m);
  const ShapeTableStats s = shape_table_stats(u.shapes, u.nodes, u.spacing);
  EXPECT_EQ(s.points, 4 * m.num_tets());
  EXPECT_LT(s.partition_error, 1e-10);
  EXPECT_LT(s.linear_error, 1e-10);
  EXPECT_LT(s.gradient_error, 1e-9);
  // Nodal values of u(x) = A x + c interpolate to A x + c and its gradient A at every Gauss point.
  Eigen::Matrix3d a;
  a << 0.01, 0.02, -0.01, 0.005, -0.02, 0.01, 0.0, 0.01, 0.03;
  const Eigen::Vector3d c(1e-4, -2e-4, 3e-4);
  double value_err = 0, grad_err = 0;
  for (int g = 0; g < u.shapes.num_points(); ++g) {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    Eigen::Matrix3d grad = Eigen::Matrix3d::Zero();
    for (int e = u.shapes.offsets[g]; e < u.shapes.offsets[g + 1]; ++e) {
      const Eigen::Vector3d ui = a * u.nodes[u.shapes.nodes[e]] + c;
      v += u.shapes.phi[e] * ui;
      grad += ui * Eigen::Vector3d(u.shapes.dphi[3 * e], u.shapes.dphi[3 * e + 1], u.shapes.dphi[3 * e + 2]).transpose();
    }
    value_err = std::max(value_err, (v - (a * u.shapes.points[g] + c)).norm());
    grad_err = std::max(grad_err, (grad - a).norm());
  }
  EXPECT_LT(value_err, 1e-12 * (a.norm() * 0.04 + c.norm()));
  EXPECT_LT(grad_err, 1e-9 * a.norm());
}

TEST(OrganScene, StiffnessIsSymmetricAndRigidModesCostNoEnergy) {
  const mesh::TetMesh m = jittered_box(4, 3, 3, {0.04, 0.03, 0.03});
  const Unsupported u = unsupported(m);
  const SparseMatrix& k = u.k;
  const SparseMatrix kt = k.transpose();
  const double scale = Eigen::MatrixXd(k).cwiseAbs().maxCoeff();
  EXPECT_LE(Eigen::MatrixXd(k - kt).cwiseAbs().maxCoeff(), 1e-14 * scale);
  const RigidModeEnergy rigid = rigid_mode_energy(k, u.nodes);
  EXPECT_LT(rigid.max_ratio, 1e-12);
  // A shear is not free: the check can fail.
  Eigen::VectorXd shear = Eigen::VectorXd::Zero(k.rows());
  for (std::size_t i = 0; i < u.nodes.size(); ++i) shear(3 * i) = u.nodes[i].y();
  EXPECT_GT(shear.dot(k * shear) / (shear.squaredNorm() * k.diagonal().mean()), 1e-3);
}

namespace {

// Every boundary node held at u(x) = A x + c by penalty, no load: the exact solution is that
// linear field everywhere (constant stress). Returns max |u − u_exact| over the interior nodes
// divided by max |u_exact|.
double patch_error(int cells) {
  const mesh::TetMesh m = jittered_box(cells, cells, cells, {0.03, 0.03, 0.03});
  MeshlessProblem p = box_problem(m, 4, 5000, 0.35);
  Eigen::Matrix3d a;
  a << 0.01, 0.02, -0.01, 0.005, -0.02, 0.01, 0.0, 0.01, 0.03;
  const Eigen::Vector3d c(1e-4, -2e-4, 3e-4);
  for (int n : m.node_sets.at("boundary")) p.constraints.push_back({n, a * m.nodes[n] + c});
  const RpimModel model(p, linear_settings());
  const Eigen::VectorXd u = model.solve(Eigen::MatrixXd::Zero(3 * m.num_nodes(), 1)).col(0);
  std::vector<char> on_surface(m.nodes.size(), 0);
  for (int n : m.node_sets.at("boundary")) on_surface[n] = 1;
  double err = 0, ref = 0;
  for (int i = 0; i < m.num_nodes(); ++i) {
    const Eigen::Vector3d exact = a * m.nodes[i] + c;
    ref = std::max(ref, exact.norm());
    if (!on_surface[i]) err = std::max(err, (u.segment<3>(3 * i) - exact).norm());
  }
  return err / ref;
}

struct FemComparison {
  double relative_rms = 0;  // RMS over nodes of |u_rpim − u_fem|, over max |u_fem|
  double tip_ratio = 0;     // u_z of RPIM / FEM at the free end's centre node
};

// A 4 × 2 × 2 cm block clamped at x = 0 and sagging under its weight (ρ g, a smooth load that
// both methods integrate consistently), solved by RPIM on the tets' nodes and Gauss points and
// by linear tetrahedra (dhd_sim's static linear solve) on the same mesh.
FemComparison compare_with_fem(int k) {
  const mesh::TetMesh m = jittered_box(2 * k, k, k, {0.04, 0.02, 0.02});
  const material::ElasticParameters elastic{5000.0, 0.35, 1000.0};
  const Eigen::Vector3d g(0, 0, -9.81);

  OrganScene scene;
  scene.youngs_modulus = elastic.youngs_modulus;
  scene.poisson_ratio = elastic.poisson_ratio;
  scene.fixed_sets = {"x_min"};
  const RpimModel rpim(organ_problem(scene, m), linear_settings());
  const Eigen::Vector3d b = elastic.density * g;
  const Eigen::VectorXd u_rpim =
      rpim.solve(rpim.body_force([b](const Eigen::Vector3d&) { return b; })).col(0);

  dynamics::Scene fem_scene;
  dynamics::DisplacementConstraint clamp;
  clamp.name = "x_min";
  clamp.nodes = m.node_sets.at("x_min");
  fem_scene.constraints.push_back(clamp);
  fem_scene.gravity = g;
  const auto fem = dynamics::solve_static(m, std::vector<fem::ElementKind>(m.num_tets(), fem::ElementKind::linear),
                                          fem::Material::make(elastic, material::NeoHookeanForm::paper), fem_scene, {});
  double sum = 0, ref = 0;
  for (int i = 0; i < m.num_nodes(); ++i) {
    const Eigen::Vector3d uf(fem.displacement[3 * i], fem.displacement[3 * i + 1], fem.displacement[3 * i + 2]);
    sum += (u_rpim.segment<3>(3 * i) - uf).squaredNorm();
    ref = std::max(ref, uf.norm());
  }
  int tip = 0;
  const Eigen::Vector3d tip_point(0.04, 0.01, 0.01);
  for (int i = 0; i < m.num_nodes(); ++i)
    if ((m.nodes[i] - tip_point).norm() < (m.nodes[tip] - tip_point).norm()) tip = i;
  return {std::sqrt(sum / m.num_nodes()) / ref, u_rpim(3 * tip + 2) / fem.displacement[3 * tip + 2]};
}

}  // namespace

// The Galerkin patch test is not exact for RPIM (supports switch nodes between Gauss points, so
// the tetrahedral quadrature does not integrate the products of shape-function gradients
// exactly: test_meshless.cpp, Convergence.GalerkinPatchTestIsPassedInTheLimit). Measured on
// these jittered boxes: 0.77 % (3 cells per edge) and 1.15 % (5): it stays at the percent level
// here rather than falling, which is what this test holds it to.
TEST(OrganScene, PatchTestIsMetToAboutOnePercent) {
  EXPECT_LT(patch_error(3), 0.02);
  EXPECT_LT(patch_error(5), 0.02);
}

// Both discretisations converge to the same continuum solution, so their difference must fall
// under refinement. Measured (RMS over nodes / largest FEM displacement): 11.9 %, 7.8 %, 4.9 %
// for k = 2, 3, 4 (a rate of about 1.3 in h; the free end's sag, RPIM / FEM: 1.20, 1.14, 1.09 —
// RPIM is the softer, as linear tetrahedra are stiff in bending). The bounds follow that
// sequence: monotone decrease, and the finest level within 6 % and its tip within 12 %.
TEST(OrganScene, AgreesWithLinearTetrahedraUnderRefinement) {
  std::vector<FemComparison> c;
  for (int k : {2, 3, 4}) c.push_back(compare_with_fem(k));
  for (std::size_t i = 1; i < c.size(); ++i) {
    EXPECT_LT(c[i].relative_rms, c[i - 1].relative_rms);
    EXPECT_LT(std::abs(c[i].tip_ratio - 1.0), std::abs(c[i - 1].tip_ratio - 1.0));
  }
  EXPECT_LT(c.back().relative_rms, 0.06);
  EXPECT_LT(std::abs(c.back().tip_ratio - 1.0), 0.12);
}
