// The linear region as assembled stiffness rows (fem/linear_rows.hpp): the rows give the same
// nodal forces as the linear elements one by one and as the reference assembly; they obey
// Maxwell–Betti reciprocity (K symmetric) and give no force under a rigid translation; only
// nodes of linear elements have rows; and the engine's tiled sweep computes every row once,
// with or without a region that is entirely linear. With single-precision stored values the
// product is the double one to the rounding of those values, and the engine stays bit-identical
// for any thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <set>

#include "softsim/dynamics/explicit_solver.hpp"
#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/dynamics/stable_step.hpp"
#include "softsim/fem/assembly.hpp"
#include "softsim/fem/element_set.hpp"
#include "softsim/fem/linear_rows.hpp"

#include "support/fields.hpp"
#include "support/scenes.hpp"

using namespace softsim;
using fem::ElementKind;
using test_scenes::cuboid;
using test_scenes::gathered_forces;
using test_scenes::kPaper;
using test_scenes::max_abs;

namespace {

const fem::Material kMaterial = fem::Material::make(kPaper, material::NeoHookeanForm::paper);

std::vector<double> random_field(const mesh::TetMesh& m, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-0.002, 0.002);
  std::vector<double> u(3 * m.nodes.size());
  for (double& x : u) x = d(rng);
  return u;
}

// Elements below mid-height linear, the rest TLED: a linear region with an interface.
std::vector<ElementKind> lower_half_linear(const mesh::TetMesh& m) {
  std::vector<ElementKind> kinds(m.num_tets(), ElementKind::tled);
  for (int e = 0; e < m.num_tets(); ++e) {
    double z = 0;
    for (int a : m.tets[e]) z += 0.25 * m.nodes[a].z();
    if (z < 0.015) kinds[e] = ElementKind::linear;
  }
  return kinds;
}

// Every node of the mesh, as a node list for multiply_rows.
std::vector<int> all_nodes(const mesh::TetMesh& m) {
  std::vector<int> nodes(m.num_nodes());
  std::iota(nodes.begin(), nodes.end(), 0);
  return nodes;
}

std::vector<double> product(const fem::LinearStiffnessRows& rows, const std::vector<int>& nodes,
                            const std::vector<double>& u,
                            fem::LinearStiffnessRows::Kernel kernel = fem::LinearStiffnessRows::Kernel::best) {
  std::vector<double> f(u.size(), 0.0);
  rows.multiply_rows(nodes.data(), nodes.data() + nodes.size(), u.data(), f.data(), kernel);
  return f;
}

// Per dof, Σ_b Σ_c |K_rc| |u_c|: rounding each stored value to float moves f_r by at most
// 2⁻²⁴ of this (a float's relative rounding), plus the double sums' own rounding.
std::vector<double> absolute_product(const fem::LinearStiffnessRows& rows, int num_nodes,
                                     const std::vector<double>& u) {
  std::vector<double> s(u.size(), 0.0);
  for (int a = 0; a < num_nodes; ++a)
    for (int p = rows.first_block(a); p < rows.first_block(a) + rows.row_blocks(a); ++p)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) s[3 * a + r] += std::abs(rows.value(p, r, c) * u[3 * rows.column_node(p) + c]);
  return s;
}

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t q = 0; q < a.size(); ++q) s += a[q] * b[q];
  return s;
}

}  // namespace

TEST(LinearRows, AssembledRowsGiveTheElementByElementForces) {
  const auto m = cuboid(4, 3, 3, 0.04, 0.03, 0.03);
  const auto kinds = lower_half_linear(m);
  const std::vector<double> u = random_field(m, 3);
  fem::ElementSet assembled(m, kinds, kMaterial, 16, fem::LinearForces::assembled);
  fem::ElementSet per_element(m, kinds, kMaterial, 16, fem::LinearForces::per_element);
  ASSERT_TRUE(assembled.assembled_linear());
  ASSERT_FALSE(per_element.assembled_linear());
  const std::vector<double> fa = gathered_forces(assembled, u);
  const std::vector<double> fe = gathered_forces(per_element, u);
  Eigen::VectorXd fr;
  fem::Assembler(m, kinds, kMaterial).internal_forces(u.data(), fr);
  const double scale = fr.lpNorm<Eigen::Infinity>();
  ASSERT_GT(scale, 0);
  for (std::size_t q = 0; q < u.size(); ++q) {
    EXPECT_NEAR(fa[q], fr[q], 1e-12 * scale) << "dof " << q;
    EXPECT_NEAR(fe[q], fr[q], 1e-12 * scale) << "dof " << q;
  }
}

TEST(LinearRows, ReciprocityAndNoForceUnderARigidTranslation) {
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);
  const std::vector<ElementKind> kinds(m.num_tets(), ElementKind::linear);
  const fem::LinearStiffnessRows rows(m, kinds, kMaterial);
  const std::vector<int> nodes = all_nodes(m);
  const auto apply = [&](const std::vector<double>& u) {
    std::vector<double> f(u.size(), 0.0);
    rows.multiply_rows(nodes.data(), nodes.data() + nodes.size(), u.data(), f.data());
    return f;
  };
  // Maxwell–Betti: the work of load case u on the displacements v equals that of v on u.
  const std::vector<double> u = random_field(m, 1), v = random_field(m, 2);
  const std::vector<double> fu = apply(u), fv = apply(v);
  EXPECT_NEAR(dot(v, fu), dot(u, fv), 1e-12 * std::sqrt(dot(fu, fu) * dot(v, v)));
  // A rigid translation strains nothing.
  std::vector<double> t(u.size());
  for (int a = 0; a < m.num_nodes(); ++a) {
    t[3 * a] = 0.003;
    t[3 * a + 1] = -0.001;
    t[3 * a + 2] = 0.002;
  }
  EXPECT_LT(max_abs(apply(t)), 1e-12 * max_abs(fu) * max_abs(t) / max_abs(u));
}

TEST(LinearRows, VectorKernelAgreesWithThePortableLoops) {
  // The vector kernel (AVX-512 or AVX2) sums in another order than the plain loops: equal to
  // rounding, over rows of every length the mesh has (whole groups of four blocks and
  // remainders) and at the last node.
  if (!fem::LinearStiffnessRows::vectorised()) GTEST_SKIP() << "this build has no vector kernel";
  const auto m = cuboid(4, 3, 3, 0.04, 0.03, 0.03);
  const fem::LinearStiffnessRows rows(m, lower_half_linear(m), kMaterial);
  const std::vector<int> nodes = all_nodes(m);
  std::set<int> lengths;
  for (int a : nodes) lengths.insert(rows.row_blocks(a) % 4);
  EXPECT_EQ(lengths.size(), 4u) << "rows should cover every remainder of four blocks";
  const std::vector<double> u = random_field(m, 5);
  std::vector<double> fv(u.size(), 0.0), fp(u.size(), 0.0);
  using Kernel = fem::LinearStiffnessRows::Kernel;
  rows.multiply_rows(nodes.data(), nodes.data() + nodes.size(), u.data(), fv.data(), Kernel::best);
  rows.multiply_rows(nodes.data(), nodes.data() + nodes.size(), u.data(), fp.data(), Kernel::portable);
  const double scale = max_abs(fp);
  ASSERT_GT(scale, 0);
  for (std::size_t q = 0; q < u.size(); ++q) EXPECT_NEAR(fv[q], fp[q], 1e-13 * scale) << "dof " << q;
}

TEST(LinearRows, OnlyNodesOfLinearElementsHaveRows) {
  const auto m = cuboid(4, 3, 3, 0.04, 0.03, 0.03);
  const auto kinds = lower_half_linear(m);
  const fem::LinearStiffnessRows rows(m, kinds, kMaterial);
  std::vector<char> linear_node(m.num_nodes(), 0);
  for (int e = 0; e < m.num_tets(); ++e)
    if (kinds[e] == ElementKind::linear)
      for (int a : m.tets[e]) linear_node[a] = 1;
  int blocks = 0;
  for (int a = 0; a < m.num_nodes(); ++a) {
    EXPECT_EQ(rows.row_blocks(a) > 0, linear_node[a] != 0) << "node " << a;
    blocks += rows.row_blocks(a);
  }
  EXPECT_EQ(blocks, rows.num_blocks());
  // Without linear elements nothing is stored, and the element set keeps no rows.
  const std::vector<ElementKind> tled(m.num_tets(), ElementKind::tled);
  EXPECT_TRUE(fem::LinearStiffnessRows(m, tled, kMaterial).empty());
  EXPECT_FALSE(fem::ElementSet(m, tled, kMaterial).assembled_linear());
}

TEST(LinearRows, TiledSweepComputesEveryRowOnceBeforeItsNodeIsGathered) {
  // Nodes of the all-linear region have no element through the buffer; they are ready in the
  // tile of their index, and their rows must be computed there.
  const auto m = cuboid(5, 4, 3, 0.05, 0.04, 0.03);
  test_scenes::expect_tiled_sweep_equals_whole_pass(m, lower_half_linear(m), kMaterial, random_field(m, 4));
}

TEST(LinearRows, SinglePrecisionValuesGiveTheDoubleProductToTheirRounding) {
  const auto m = cuboid(4, 3, 3, 0.04, 0.03, 0.03);
  const auto kinds = lower_half_linear(m);
  const std::vector<int> nodes = all_nodes(m);
  const std::vector<double> u = random_field(m, 6);
  const fem::LinearStiffnessRows exact(m, kinds, kMaterial);
  fem::LinearStiffnessRows rows(m, kinds, kMaterial);
  rows.set_precision(fem::LinearPrecision::single_precision);
  const std::vector<double> fd = product(exact, nodes, u), fs = product(rows, nodes, u);
  const std::vector<double> bound = absolute_product(exact, m.num_nodes(), u);
  double largest_change = 0;
  for (std::size_t q = 0; q < u.size(); ++q) {
    EXPECT_LE(std::abs(fs[q] - fd[q]), std::ldexp(bound[q], -24) * (1 + 1e-6) + 1e-15 * bound[q]) << "dof " << q;
    largest_change = std::max(largest_change, std::abs(fs[q] - fd[q]));
  }
  EXPECT_GT(largest_change, 0.0) << "the stored values should have been rounded";
  // The vector kernel and the plain loops read the same float values.
  if (fem::LinearStiffnessRows::vectorised()) {
    const std::vector<double> fp = product(rows, nodes, u, fem::LinearStiffnessRows::Kernel::portable);
    for (std::size_t q = 0; q < u.size(); ++q) EXPECT_NEAR(fs[q], fp[q], 1e-13 * max_abs(fp)) << "dof " << q;
  }
  // Back to double: the double blocks were kept, the product is theirs bit for bit.
  rows.set_precision(fem::LinearPrecision::double_precision);
  EXPECT_EQ(product(rows, nodes, u), fd);
}

TEST(LinearRows, SinglePrecisionRowsFollowARemovedElement) {
  // A cut removes a linear element: the double blocks lose its share and the touched blocks are
  // rounded again, so the product is that of the rows without it, to the float rounding.
  const auto m = cuboid(4, 3, 3, 0.04, 0.03, 0.03);
  auto kinds = lower_half_linear(m);
  const std::vector<int> nodes = all_nodes(m);
  const std::vector<double> u = random_field(m, 7);
  fem::LinearStiffnessRows rows(m, kinds, kMaterial);
  rows.set_precision(fem::LinearPrecision::single_precision);
  const int removed = static_cast<int>(std::find(kinds.begin(), kinds.end(), ElementKind::linear) - kinds.begin());
  rows.remove_element(m, removed, kMaterial);
  kinds[removed] = ElementKind::tled;
  const fem::LinearStiffnessRows without(m, kinds, kMaterial);
  const std::vector<double> fs = product(rows, nodes, u), fd = product(without, nodes, u);
  const std::vector<double> bound = absolute_product(without, m.num_nodes(), u);
  const double scale = max_abs(fd);
  for (std::size_t q = 0; q < u.size(); ++q)
    EXPECT_LE(std::abs(fs[q] - fd[q]), std::ldexp(bound[q], -24) * (1 + 1e-6) + 1e-12 * scale) << "dof " << q;
}

TEST(LinearRows, SinglePrecisionRunsAreBitIdenticalForAnyThreadCount) {
  const auto m = cuboid(5, 4, 4, 0.05, 0.04, 0.04);
  const fem::Material mat = fem::Material::make(kPaper, material::NeoHookeanForm::paper);
  const auto kinds = lower_half_linear(m);
  dynamics::Scene scene;
  scene.constraints = {test_scenes::constraint(m, "bottom", Eigen::Vector3d::Zero()),
                       test_scenes::constraint(m, "top", Eigen::Vector3d(0.001, 0.0, -0.006))};
  scene.constraints[1].ramp.duration = 0.05;
  dynamics::ExplicitOptions opt;
  opt.dt = 0.9 * dynamics::critical_time_step(m, kPaper).dt;
  opt.steps = 150;
  opt.energy_interval = 50;
  const auto run = [&](int threads, fem::LinearPrecision precision) {
    fem::ElementSet set(m, kinds, mat, 16);  // small tiles: the threads share the sweep
    set.set_linear_precision(precision);
    opt.threads = threads;
    dynamics::ExplicitSolver solver(set, dynamics::lumped_mass(m, kPaper.density), scene, opt);
    return solver.run().displacement;
  };
  const std::vector<double> one = run(1, fem::LinearPrecision::single_precision);
  const std::vector<double> two = run(2, fem::LinearPrecision::single_precision);
  const std::vector<double> three = run(3, fem::LinearPrecision::single_precision);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(0, std::memcmp(one.data(), two.data(), one.size() * sizeof(double)));
  EXPECT_EQ(one, three);
  // And the option is a small change of the double run, not another result.
  const std::vector<double> exact = run(1, fem::LinearPrecision::double_precision);
  EXPECT_GT(test_scenes::max_abs_diff(one, exact), 0.0);
  EXPECT_LT(test_scenes::max_abs_diff(one, exact), 1e-5 * max_abs(exact));
}
