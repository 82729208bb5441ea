// The RPIM meshless model of 002 §2: interpolation properties of the shape functions, the
// Galerkin stiffness (symmetry, rigid-body modes, reciprocity), penalty supports, the plate
// scene of 002 §4.1, and convergence to an exact elasticity solution under node refinement.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#ifdef SOFTSIM_HAVE_OPENMP
#include <omp.h>
#endif

#include "softsim/io/errors.hpp"
#include "softsim/meshless/assembly.hpp"
#include "softsim/meshless/conditioning.hpp"
#include "softsim/meshless/gauss_legendre.hpp"
#include "softsim/meshless/lee_radok.hpp"
#include "softsim/meshless/load_cases.hpp"
#include "softsim/meshless/manufactured.hpp"
#include "softsim/meshless/plate_dataset.hpp"
#include "softsim/meshless/rpim_config.hpp"
#include "softsim/meshless/rpim_modes.hpp"
#include "softsim/meshless/rpim_shape.hpp"
#include "softsim/meshless/studies.hpp"

using namespace softsim;
using namespace softsim::meshless;

namespace {

// A jittered 4 × 4 × 3 cloud in a 3 × 3 × 2 box: irregular enough that no symmetry hides an error.
Eigen::MatrixX3d scattered_nodes() {
  Eigen::MatrixX3d x(48, 3);
  int r = 0;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i, ++r) {
        const double s = std::sin(1.7 * r + 0.3), c = std::cos(2.3 * r + 0.1);
        x.row(r) << i + 0.2 * s, j + 0.2 * c, k + 0.15 * s * c;
      }
  return x;
}

RbfParams rbf(PolynomialBasis poly, double q = 1.03) {
  RbfParams p;
  p.alpha_c = 1.0;
  p.d_c = 1.0;
  p.q = q;
  p.polynomial = poly;
  return p;
}

SparseMatrix plate_stiffness(const PlateScene& scene, const RpimSettings& settings) {
  const MeshlessProblem p = plate_problem(scene);
  const ShapeTable t = build_shape_table(p.nodes, box_quadrature(p.origin, p.size, p.cells, p.gauss_order),
                                         resolve_support(settings, plate_mean_spacing(scene)),
                                         resolve_rbf(settings, plate_mean_spacing(scene)));
  return assemble_stiffness(t, static_cast<int>(p.nodes.size()), lame_from_young(p.youngs_modulus, p.poisson_ratio));
}

RpimSettings augmented() {
  RpimSettings s;
  s.polynomial = PolynomialBasis::linear;
  return s;
}

}  // namespace

// ---------------------------------------------------------------- quadrature

namespace {

// Every order rpim_precompute accepts (plate.gauss_order and block.gauss_order: 1 to 10).
constexpr int kMaxConfigOrder = 10;

// The rule as this project computed it before it used GSL's: Newton's method on P_n from a
// Chebyshev-like start, the weights from P_n' at the root.
GaussRule newton_gauss_legendre(int n) {
  GaussRule rule{std::vector<double>(n), std::vector<double>(n)};
  const auto legendre = [n](double x) {  // (P_n(x), P_n'(x))
    double p0 = 1, p1 = x;
    for (int k = 2; k <= n; ++k) {
      const double pk = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
      p0 = p1;
      p1 = pk;
    }
    return std::pair{p1, n * (x * p1 - p0) / (x * x - 1)};
  };
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(std::acos(-1.0) * (i + 0.75) / (n + 0.5));
    for (int iter = 0; iter < 100; ++iter) {
      const auto [p, dp] = legendre(x);
      x -= p / dp;
      if (std::abs(p / dp) < 1e-16) break;
    }
    const double dp = legendre(x).second;
    rule.points[i] = -x;
    rule.points[n - 1 - i] = x;
    rule.weights[i] = rule.weights[n - 1 - i] = 2.0 / ((1 - x * x) * dp * dp);
  }
  if (n % 2 == 1) rule.points[n / 2] = 0.0;
  return rule;
}

}  // namespace

TEST(GaussLegendre, ExactForDegree2nMinus1ToRoundOff) {
  // Summed in long double, so that what remains is the rounding of the rule's own points and
  // weights: correctly rounded values leave less than one double epsilon on ∫x^d over [-1, 1].
  const double eps = std::numeric_limits<double>::epsilon();
  for (int n = 1; n <= kMaxConfigOrder; ++n) {
    const GaussRule r = gauss_legendre(n);
    ASSERT_EQ(r.points.size(), static_cast<std::size_t>(n));
    for (int i = 1; i < n; ++i) EXPECT_LT(r.points[i - 1], r.points[i]) << "n = " << n;
    for (int degree = 0; degree <= 2 * n - 1; ++degree) {
      long double sum = 0;
      for (int i = 0; i < n; ++i) sum += static_cast<long double>(r.weights[i]) * std::pow(static_cast<long double>(r.points[i]), degree);
      const long double exact = degree % 2 ? 0.0L : 2.0L / (degree + 1);
      EXPECT_LE(std::abs(sum - exact), eps) << "n = " << n << ", degree " << degree;
    }
  }
}

TEST(GaussLegendre, MatchesTheNewtonRuleToRoundOff) {
  // The Newton weights carry up to about 20 ulp (P_n' near a root loses digits); the points agree
  // to an ulp or two. Beyond that the two rules must not differ.
  const double eps = std::numeric_limits<double>::epsilon();
  for (int n = 1; n <= kMaxConfigOrder; ++n) {
    const GaussRule gsl = gauss_legendre(n), newton = newton_gauss_legendre(n);
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(gsl.points[i], newton.points[i], 2 * eps) << "n = " << n << ", point " << i;
      EXPECT_NEAR(gsl.weights[i], newton.weights[i], 32 * eps * gsl.weights[i]) << "n = " << n << ", weight " << i;
    }
  }
}

TEST(BlockStudyConfig, MissingBlockAndEmptyBlockReadTheSameDocumentedDefaults) {
  // rpim_precompute.md: block.gauss_order defaults to 3, whether "block" is absent or empty.
  const nlohmann::json without = nlohmann::json::object(), with_empty = {{"block", nlohmann::json::object()}};
  const io::JsonReader config(without, "run.json"), empty(with_empty, "run.json");  // readers refer to the values
  const BlockStudy absent = read_block_study(config.optional("block"));
  const BlockStudy given = read_block_study(empty.optional("block"));
  EXPECT_EQ(absent.gauss_order, 3);
  EXPECT_EQ(given.gauss_order, 3);
  EXPECT_EQ(absent.nodes_per_edge, given.nodes_per_edge);
  EXPECT_EQ(absent.edge, given.edge);
}

TEST(BackgroundCells, WeightsSumToBoxVolume) {
  const QuadraturePoints q = box_quadrature(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.048, 0.048, 0.006), {8, 8, 1}, 4);
  EXPECT_EQ(q.points.size(), 64u * 64u);  // 002 §4.1: 64 cells
  double v = 0;
  for (double w : q.weights) v += w;
  EXPECT_NEAR(v, 0.048 * 0.048 * 0.006, 1e-18);
}

// ---------------------------------------------------------------- shape functions (002 eqs. 11-17)

TEST(RpimShape, KroneckerDeltaAtNodes) {
  const Eigen::MatrixX3d x = scattered_nodes();
  for (const auto poly : {PolynomialBasis::none, PolynomialBasis::linear}) {
    RpimShapeEvaluator ev(rbf(poly));
    ShapeValues v;
    for (int j = 0; j < x.rows(); j += 5) {
      ev.evaluate(x.row(j).transpose(), x, false, v);
      for (int i = 0; i < x.rows(); ++i) EXPECT_NEAR(v.phi[i], i == j ? 1.0 : 0.0, 1e-9) << "node " << j;
    }
  }
}

TEST(RpimShape, LinearAugmentationReproducesLinearFieldsAndGradients) {
  const Eigen::MatrixX3d x = scattered_nodes();
  RpimShapeEvaluator ev(rbf(PolynomialBasis::linear));
  ShapeValues v;
  for (const Eigen::Vector3d p : {Eigen::Vector3d(1.3, 1.7, 0.9), Eigen::Vector3d(0.1, 2.9, 1.8)}) {
    ev.evaluate(p, x, true, v);
    EXPECT_NEAR(v.phi.sum(), 1.0, 1e-11);
    EXPECT_LT((x.transpose() * v.phi - p).norm(), 1e-10);
    EXPECT_LT(v.dphi.colwise().sum().norm(), 1e-10);
    EXPECT_LT((x.transpose() * v.dphi - Eigen::Matrix3d::Identity()).norm(), 1e-9);
  }
}

TEST(RpimShape, PureMultiquadricDoesNotReproduceConstantsExactly) {
  // 002 eq. 12 drops the polynomial: the partition of unity then only holds approximately,
  // which is why the paper's variant cannot pass the patch test.
  const Eigen::MatrixX3d x = scattered_nodes();
  RpimShapeEvaluator ev(rbf(PolynomialBasis::none));
  ShapeValues v;
  ev.evaluate(Eigen::Vector3d(1.3, 1.7, 0.9), x, true, v);
  const double error = std::abs(v.phi.sum() - 1.0);
  EXPECT_GT(error, 1e-8);
  EXPECT_LT(error, 1e-2);
}

TEST(RpimShape, GradientMatchesFiniteDifferences) {
  const Eigen::MatrixX3d x = scattered_nodes();
  for (const auto poly : {PolynomialBasis::none, PolynomialBasis::linear}) {
    RpimShapeEvaluator ev(rbf(poly));
    ShapeValues v, plus, minus;
    const Eigen::Vector3d p(1.4, 1.1, 0.7);
    ev.evaluate(p, x, true, v);
    const double h = 1e-5;
    for (int k = 0; k < 3; ++k) {
      ev.evaluate(p + h * Eigen::Vector3d::Unit(k), x, false, plus);
      ev.evaluate(p - h * Eigen::Vector3d::Unit(k), x, false, minus);
      const Eigen::VectorXd fd = (plus.phi - minus.phi) / (2 * h);
      EXPECT_LT((fd - v.dphi.col(k)).cwiseAbs().maxCoeff(), 1e-6) << "direction " << k;
    }
  }
}

TEST(RpimShape, InvariantUnderTranslationAndScaling) {
  // Coordinates in mm or m, shifted anywhere: the same shape functions when d_c scales too.
  const Eigen::MatrixX3d x = scattered_nodes();
  const Eigen::Vector3d p(1.3, 1.7, 0.9), shift(10.0, -4.0, 2.5);
  const double scale = 1e-3;
  RpimShapeEvaluator a(rbf(PolynomialBasis::none));
  RbfParams scaled = rbf(PolynomialBasis::none);
  scaled.d_c *= scale;
  RpimShapeEvaluator b(scaled);
  ShapeValues va, vb;
  a.evaluate(p, x, true, va);
  const Eigen::MatrixX3d y = ((x.rowwise() + shift.transpose()) * scale).eval();
  b.evaluate((p + shift) * scale, y, true, vb);
  EXPECT_LT((va.phi - vb.phi).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((va.dphi - vb.dphi * scale).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(RpimShape, SingularMomentMatrixIsANumericalErrorNotGarbage) {
  // q = 1 makes R(r) = r² + c² a quadratic polynomial: R_s has rank <= 5, so the moment
  // matrix of 48 nodes is singular. So is q = 2 (a quartic).
  const Eigen::MatrixX3d x = scattered_nodes();
  for (const double q : {1.0, 2.0}) {
    RpimShapeEvaluator ev(rbf(PolynomialBasis::none, q));
    ShapeValues v;
    try {
      ev.evaluate(Eigen::Vector3d(1.3, 1.7, 0.9), x, true, v);
      FAIL() << "q = " << q << " accepted";
    } catch (const NumericalError& e) {
      EXPECT_NE(std::string(e.what()).find("moment matrix"), std::string::npos);
      EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos);
    }
  }
}

// ---------------------------------------------------------------- stiffness (002 eqs. 7, 19-22)

namespace {

// The textbook Voigt form, the independent reference of the closed-form block. Strain order
// ε = [εxx, εyy, εzz, γyz, γxz, γxy] (rows of L in 002 eq. 4).
// D of 002 eq. 7: D11 = E(1-ν)/((1+ν)(1-2ν)), D12 = Eν/((1+ν)(1-2ν)), shear (D11 - D12)/2.
Eigen::Matrix<double, 6, 6> elasticity_matrix(double e, double nu) {
  const double f = e / ((1 + nu) * (1 - 2 * nu));
  const double d11 = f * (1 - nu), d12 = f * nu;  // 002 eq. 7
  Eigen::Matrix<double, 6, 6> d = Eigen::Matrix<double, 6, 6>::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) d(i, j) = i == j ? d11 : d12;
  for (int i = 3; i < 6; ++i) d(i, i) = 0.5 * (d11 - d12);
  return d;
}

// B_i = L Φ_i (002 eqs. 18–19): the 6 × 3 strain matrix of one node from its gradient.
Eigen::Matrix<double, 6, 3> strain_matrix(const Eigen::Vector3d& g) {
  Eigen::Matrix<double, 6, 3> b = Eigen::Matrix<double, 6, 3>::Zero();
  b(0, 0) = g.x();                    // εxx = ∂u/∂x
  b(1, 1) = g.y();                    // εyy = ∂v/∂y
  b(2, 2) = g.z();                    // εzz = ∂w/∂z
  b(3, 1) = g.z(); b(3, 2) = g.y();   // γyz = ∂v/∂z + ∂w/∂y
  b(4, 0) = g.z(); b(4, 2) = g.x();   // γxz = ∂u/∂z + ∂w/∂x
  b(5, 0) = g.y(); b(5, 1) = g.x();   // γxy = ∂u/∂y + ∂v/∂x
  return b;
}

}  // namespace

TEST(Elasticity, ClosedFormBlockEqualsBTransposeDB) {
  const Eigen::Vector3d gi(0.3, -1.2, 0.7), gj(-0.4, 0.25, 1.1);
  const double e = 0.32e6, nu = 0.49, w = 0.37;
  const Eigen::Matrix3d reference = w * strain_matrix(gi).transpose() * elasticity_matrix(e, nu) * strain_matrix(gj);
  Eigen::Matrix<double, 3, 3, Eigen::RowMajor> block = Eigen::Matrix3d::Zero();
  add_stiffness_block(gi.data(), gj.data(), w, lame_from_young(e, nu), block.data());
  EXPECT_LT((block - reference).norm(), 1e-12 * reference.norm());
}

TEST(Stiffness, IsSymmetric) {
  const SparseMatrix k = plate_stiffness(PlateScene{}, RpimSettings{});
  const SparseMatrix kt = k.transpose();
  const double asym = (k - kt).norm(), scale = k.norm();
  EXPECT_LT(asym, 1e-13 * scale);
}

TEST(Stiffness, RigidBodyModesCostNoEnergyBeforeBoundaryConditions) {
  PlateScene scene;
  const SparseMatrix k = plate_stiffness(scene, augmented());
  const RigidModeEnergy r = rigid_mode_energy(k, plate_nodes(scene));
  // A simple shear u_x = y of the same amplitude is just as smooth but deforms the plate: its
  // energy on this scale is small ((h/L)²) but must exceed the rigid modes' by many decades.
  Eigen::VectorXd u = Eigen::VectorXd::Zero(k.rows());
  const auto nodes = plate_nodes(scene);
  for (std::size_t i = 0; i < nodes.size(); ++i) u[3 * i] = nodes[i].y();
  const double shear = u.dot(k * u) / (u.squaredNorm() * k.diagonal().mean());
  EXPECT_LT(r.max_ratio, 1e-14);
  EXPECT_LT(r.max_ratio, 1e-9 * shear);
}

TEST(Stiffness, UnconstrainedModelIsRefusedAsSingular) {
  PlateScene scene;
  const SparseMatrix k = plate_stiffness(scene, augmented());
  StiffnessSolver solver;
  EXPECT_THROW(solver.factorize(k), NumericalError);
}

TEST(Stiffness, BitIdenticalForAnyThreadCount) {
#ifdef SOFTSIM_HAVE_OPENMP
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const SparseMatrix one = plate_stiffness(PlateScene{}, RpimSettings{});
  omp_set_num_threads(std::max(2, saved));
  const SparseMatrix many = plate_stiffness(PlateScene{}, RpimSettings{});
  omp_set_num_threads(saved);
  ASSERT_EQ(one.nonZeros(), many.nonZeros());
  for (Eigen::Index i = 0; i < one.nonZeros(); ++i) ASSERT_EQ(one.valuePtr()[i], many.valuePtr()[i]);
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

TEST(BodyForce, ConsistentLoadsSumToTheTotalForce) {
  // With a partition of unity Σ_I F^b_I = ∫ b dΩ (002 eq. 24).
  PlateScene scene;
  const RpimModel model(plate_problem(scene), augmented());
  const Eigen::Vector3d b(0, 0, -1060 * 9.81);
  const Eigen::VectorXd f = model.body_force([&](const Eigen::Vector3d&) { return b; });
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (int i = 0; i < model.num_nodes(); ++i) total += f.segment<3>(3 * i);
  EXPECT_LT((total - b * scene.size.prod()).norm(), 1e-10 * b.norm() * scene.size.prod());
}

// ---------------------------------------------------------------- penalty supports (002 eqs. 28-29)

TEST(Penalty, FixedNodesStayAtTheirPrescribedDisplacement) {
  for (const auto kind : {PenaltyParams::Kind::scale_block, PenaltyParams::Kind::add_diagonal}) {
    PlateScene scene;
    MeshlessProblem p = plate_problem(scene);
    for (auto& c : p.constraints) c.value = Eigen::Vector3d(1e-4, -2e-4, 0.5e-4);  // a prescribed shift
    RpimSettings s;
    s.penalty.kind = kind;
    s.penalty.lambda = 1e8;
    const RpimModel model(p, s);
    const Eigen::VectorXd u = model.solve(Eigen::VectorXd::Zero(3 * model.num_nodes()));
    for (const auto& c : p.constraints)
      EXPECT_LT((u.segment<3>(3 * c.node) - c.value).norm(), 1e-6 * c.value.norm());
  }
}

// ---------------------------------------------------------------- the plate (002 §4.1)

TEST(Plate, PaperNodeNumberingAndSupports) {
  PlateScene s;
  const auto nodes = plate_nodes(s);
  ASSERT_EQ(nodes.size(), 363u);
  const auto top = plate_top_nodes(s);
  ASSERT_EQ(top.size(), 121u);
  EXPECT_EQ(plate_loaded_node_number(s), 61);
  EXPECT_LT((nodes[top[60]] - Eigen::Vector3d(0.024, 0.024, 0.006)).norm(), 1e-15);
  // N = x/4.8 + 11 y/4.8 + 1 (002 §4.1), x, y in mm.
  for (int n = 0; n < 121; ++n) {
    const Eigen::Vector3d x = nodes[top[n]] * 1e3;
    EXPECT_EQ(static_cast<int>(std::lround(x.x() / 4.8 + 11 * x.y() / 4.8 + 1)), n + 1);
  }
  s.supports = PlateSupports::side_faces;
  EXPECT_EQ(plate_fixed_nodes(s).size(), 120u);
  s.supports = PlateSupports::bottom_edges;
  EXPECT_EQ(plate_fixed_nodes(s).size(), 40u);
  s.supports = PlateSupports::vertical_corner_edges;
  EXPECT_EQ(plate_fixed_nodes(s).size(), 12u);  // includes top corners 1, 11, 111, 121
}

TEST(Plate, ResponseRespectsTheSquareSymmetry) {
  // A square plate with symmetric supports: F_y produces the mirror image of F_x under the
  // swap x <-> y, and F_z a field symmetric about both mid-planes.
  PlateScene scene;
  const PlateRun run = run_plate(scene, RpimSettings{}, {}, false);
  const int nx = scene.nodes[0];
  double scale = run.unit_solutions.cwiseAbs().maxCoeff(), worst = 0;
  for (int j = 0; j < nx; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = run.top_nodes[i + nx * j], b = run.top_nodes[j + nx * i];  // swapped
      const int m = run.top_nodes[(nx - 1 - i) + nx * j];                        // x mirror
      const Eigen::Vector3d ux = run.unit_solutions.col(0).segment<3>(3 * a);
      const Eigen::Vector3d uy = run.unit_solutions.col(1).segment<3>(3 * b);
      worst = std::max(worst, (Eigen::Vector3d(uy.y(), uy.x(), uy.z()) - ux).norm());
      const Eigen::Vector3d uz = run.unit_solutions.col(2).segment<3>(3 * a);
      const Eigen::Vector3d uzm = run.unit_solutions.col(2).segment<3>(3 * m);
      worst = std::max(worst, (Eigen::Vector3d(-uzm.x(), uzm.y(), uzm.z()) - uz).norm());
    }
  EXPECT_LT(worst, 1e-8 * scale);
}

TEST(Plate, ReciprocityOfMaxwellBetti) {
  // u_a(A) under a unit force along b at B equals u_b(B) under a unit force along a at A.
  PlateScene scene;
  const RpimModel model(plate_problem(scene), RpimSettings{});
  const int a_node = plate_node_index(scene, 3, 4, 2), b_node = plate_node_index(scene, 7, 2, 1);
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(3 * model.num_nodes(), 2);
  f(3 * a_node + 0, 0) = 1.0;  // x at A
  f(3 * b_node + 2, 1) = 1.0;  // z at B
  const Eigen::MatrixXd u = model.solve(f);
  EXPECT_NEAR(u(3 * b_node + 2, 0), u(3 * a_node + 0, 1), 1e-9 * std::abs(u(3 * a_node + 0, 0)));
}

TEST(Plate, DatasetCasesAreSuperpositionsOfTheUnitSolutions) {
  DatasetSpec spec;
  spec.kind = DatasetKind::random;
  spec.count = 20;
  spec.seed = 11;
  const PlateRun run = run_plate(PlateScene{}, RpimSettings{}, dataset_forces(spec), false);
  const double scale = run.unit_solutions.cwiseAbs().maxCoeff();
  for (int c = 0; c < spec.count; ++c) {
    const Eigen::VectorXd expected = run.unit_solutions * run.forces[c];
    EXPECT_LT((run.displacements.col(c) - expected).cwiseAbs().maxCoeff(), 1e-10 * scale);
  }
}

TEST(Plate, LoadedNodeMovesWithTheForceAndStiffensWithMoreSupports) {
  // Positive compliance along each axis, and the more the plate is held the stiffer it is.
  double previous = INFINITY;
  for (const auto sup : {PlateSupports::vertical_corner_edges, PlateSupports::bottom_edges, PlateSupports::side_faces}) {
    PlateScene scene;
    scene.supports = sup;
    const PlateRun run = run_plate(scene, RpimSettings{}, {}, false);
    const int l = run.loaded_node_index;
    for (int a = 0; a < 3; ++a) EXPECT_GT(run.unit_solutions(3 * l + a, a), 0.0);
    const double cz = run.unit_solutions(3 * l + 2, 2);
    EXPECT_LT(cz, previous) << supports_name(sup);
    previous = cz;
  }
}

TEST(Plate, SingularShapeParametersFailWithAMessage) {
  RpimSettings s;
  s.q = 1.0;
  try {
    run_plate(PlateScene{}, s, {}, false);
    FAIL() << "q = 1 accepted";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("moment matrix"), std::string::npos);
  }
}

// ---------------------------------------------------------------- datasets (002 §4.2)

TEST(LoadCases, AxisMagnitudesAndReproducibleRandomForces) {
  DatasetSpec axis;
  axis.kind = DatasetKind::axis_y;
  axis.count = 5;
  const auto f = dataset_forces(axis);
  ASSERT_EQ(f.size(), 5u);
  for (int k = 0; k < 5; ++k) EXPECT_LT((f[k] - Eigen::Vector3d(0, 0.2 * (k + 1), 0)).norm(), 1e-15);

  DatasetSpec random;
  random.kind = DatasetKind::random;
  random.count = 100;
  random.seed = 42;
  const auto a = dataset_forces(random), b = dataset_forces(random);
  random.seed = 43;
  const auto c = dataset_forces(random);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int k = 0; k < 100; ++k) {
    EXPECT_EQ(a[k], b[k]);
    EXPECT_LE(a[k].norm(), 1.0);
    mean += a[k].normalized() / 100.0;
  }
  EXPECT_NE(a[0], c[0]);
  EXPECT_LT(mean.norm(), 0.3);  // directions spread over the sphere (|mean| ~ 0.1 expected)
}

// ---------------------------------------------------------------- material (002 eqs. 47-48)

TEST(LeeRadok, IncompressibleLimitIsHertzContact) {
  // Hertz: F = (4/3) E/(1-ν²) √R δ^(3/2); at ν = 1/2 this is (16/3) G √R δ^(3/2).
  const double e = 0.32e6, nu = 0.4999999, r = 0.002, d = 0.0006;
  const double f = 4.0 / 3.0 * e / (1 - nu * nu) * std::sqrt(r) * std::pow(d, 1.5);
  const IndentationModulus m = lee_radok_modulus(f, d, r, nu);
  EXPECT_NEAR(m.youngs_modulus, e, 1e-6 * e);
  EXPECT_NEAR(m.shear_modulus, e / (2 * (1 + nu)), 1e-6 * e);
}

// ---------------------------------------------------------------- conditioning

TEST(Conditioning, LanczosMatchesDenseEigenvalues) {
  PlateScene scene;
  scene.nodes = {5, 5, 3};
  scene.background_cells = {4, 4, 1};
  scene.gauss_order = 3;
  const RpimModel model(plate_problem(scene), augmented());
  const SpectrumEstimate s = estimate_spectrum(model.penalized_stiffness(), model.solver());
  const Eigen::VectorXd eig =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(model.penalized_stiffness()), Eigen::EigenvaluesOnly)
          .eigenvalues();
  EXPECT_NEAR(s.lambda_max, eig.maxCoeff(), 1e-8 * eig.maxCoeff());
  EXPECT_NEAR(s.lambda_min, eig.minCoeff(), 1e-6 * eig.minCoeff());
}

// ---------------------------------------------------------------- convergence (002 eq. 1 exactly solved)

TEST(Convergence, PlaneWaveErrorFallsWithNodeRefinement) {
  // u = c sin(a·x) with its body force, all boundary nodes held at the exact values. Liu and
  // Gu's recommended shape (α_c = 4, d_c = nodal spacing), linear augmentation, supports of
  // 3 spacings: a linear-complete approximation converges at about second order in the nodal
  // error; the boundary treatment by nodal penalty costs some of it.
  RpimSettings s;
  s.polynomial = PolynomialBasis::linear;
  s.alpha_c = 4.0;
  s.d_c = {LengthSpec::Kind::spacing_factor, 1.0};
  s.support_radius = {LengthSpec::Kind::spacing_factor, 3.0};
  BlockStudy block;
  block.gauss_order = 3;
  const auto study = convergence_study(block, s, {4, 5, 7});
  std::vector<double> h, e;
  for (std::size_t i = 0; i < study.size(); ++i) {
    h.push_back(study[i].result.spacing);
    e.push_back(study[i].result.rms_error);
    if (i > 0) EXPECT_LT(e[i], e[i - 1]) << "nodes per edge " << study[i].nodes_per_edge;
  }
  EXPECT_GT(observed_rate(h, e), 1.5);
  EXPECT_LT(study.back().result.relative_rms(), 5e-3);
}

TEST(Convergence, GalerkinPatchTestIsPassedInTheLimit) {
  // Linear displacement, constant stress, no body force. The shape functions reproduce it
  // exactly (see LinearAugmentation...), but RPIM's Galerkin form does not pass the patch test
  // exactly: supports switch nodes between Gauss points (shape functions are discontinuous
  // there, so quadrature is inexact) and interior test functions do not vanish between
  // boundary nodes. The error must vanish as the nodes are refined.
  RpimSettings s;
  s.polynomial = PolynomialBasis::linear;
  s.alpha_c = 4.0;
  s.d_c = {LengthSpec::Kind::spacing_factor, 1.0};
  BlockStudy block;
  block.field = ManufacturedField::linear_patch;
  block.gauss_order = 3;
  const auto study = convergence_study(block, s, {4, 5, 7});
  for (std::size_t i = 1; i < study.size(); ++i)
    EXPECT_LT(study[i].result.rms_error, study[i - 1].result.rms_error);
  EXPECT_LT(study.back().result.relative_rms(), 1e-3);
}

// The Lanczos estimate of K's condition runs only when the config asks for it; the cases, unit
// solutions and every other conditioning figure are the same bits either way.
TEST(Dataset, StiffnessConditioningOnlyWhenAsked) {
  const nlohmann::json base = {{"plate", {{"nodes", {5, 5, 2}}, {"background_cells", {4, 4, 1}}, {"gauss_order", 3}}},
                               {"rpim", {{"polynomial", "linear"}}},
                               {"dataset", {{"kind", "axis_z"}, {"count", 3}}}};
  const nlohmann::json asked_cfg = [&] {
    nlohmann::json j = base;
    j["output"] = {{"stiffness_conditioning", true}};
    return j;
  }();
  const RpimOutput plain = run_rpim_mode("dataset", io::JsonReader(base, "run.json"));
  const RpimOutput asked = run_rpim_mode("dataset", io::JsonReader(asked_cfg, "run.json"));
  const nlohmann::json& c0 = plain.payload.at("conditioning");
  const nlohmann::json& c1 = asked.payload.at("conditioning");
  EXPECT_TRUE(c0.at("stiffness_penalized").is_null());
  EXPECT_TRUE(c0.at("stiffness_free_dofs").is_null());
  ASSERT_FALSE(c1.at("stiffness_free_dofs").is_null());
  EXPECT_GT(c1.at("stiffness_free_dofs").at("condition").get<double>(), 1.0);
  EXPECT_GT(c1.at("stiffness_penalized").at("condition").get<double>(), 1.0);
  EXPECT_EQ(plain.payload.at("cases"), asked.payload.at("cases"));
  EXPECT_EQ(plain.payload.at("unit_solutions"), asked.payload.at("unit_solutions"));
  nlohmann::json rest0 = c0, rest1 = c1;
  for (auto* r : {&rest0, &rest1}) {
    r->erase("stiffness_penalized");
    r->erase("stiffness_free_dofs");
  }
  EXPECT_EQ(rest0, rest1);
}

// Several datasets of one plate ("datasets") are built and factored once, and each member is
// the payload its own single run writes, bit for bit (timings aside).
TEST(Dataset, NamedSetsShareOneBuildAndEqualTheSingleRuns) {
  const nlohmann::json plate = {{"nodes", {5, 5, 2}}, {"background_cells", {4, 4, 1}}, {"gauss_order", 3}};
  const nlohmann::json specs = {{"x", {{"kind", "axis_x"}, {"count", 3}}},
                                {"random", {{"kind", "random"}, {"count", 4}, {"seed", 7}}},
                                {"check", {{"kind", "check"}}}};
  const nlohmann::json indentation = {{"force", 0.4}, {"depth", 0.006}, {"probe_radius", 0.002}, {"poisson_ratio", 0.49}};
  const nlohmann::json rpim = {{"polynomial", "linear"}};  // so few nodes need it
  const nlohmann::json set_cfg = {{"plate", plate}, {"rpim", rpim}, {"datasets", specs}, {"indentation", indentation}};
  const RpimOutput set = run_rpim_mode("dataset", io::JsonReader(set_cfg, "run.json"));
  EXPECT_EQ(set.schema, "rpim_dataset_set");
  ASSERT_TRUE(set.seed.has_value());
  EXPECT_EQ(*set.seed, 7u);
  const nlohmann::json& members = set.payload.at("members");
  ASSERT_EQ(members.size(), 3u);
  EXPECT_EQ(set.payload.at("timing").at("datasets"), 3);
  for (const auto& [name, spec] : specs.items()) {
    const nlohmann::json one_cfg = {{"plate", plate}, {"rpim", rpim}, {"dataset", spec}, {"indentation", indentation}};
    const RpimOutput one = run_rpim_mode("dataset", io::JsonReader(one_cfg, "run.json"));
    EXPECT_EQ(one.schema, "rpim_dataset");
    nlohmann::json a = one.payload, b = members.at(name);
    EXPECT_EQ(a.at("timing").at("cases_solved"), b.at("timing").at("cases_solved")) << name;
    a.erase("timing");
    b.erase("timing");
    EXPECT_EQ(a, b) << name;  // cases, unit solutions, conditioning, plate, model: the same bits
  }
  // Exactly one of "dataset" and "datasets".
  nlohmann::json both = set_cfg;
  both["dataset"] = specs.at("x");
  EXPECT_THROW(run_rpim_mode("dataset", io::JsonReader(both, "run.json")), InputError);
  const nlohmann::json neither = {{"plate", plate}, {"rpim", rpim}};
  EXPECT_THROW(run_rpim_mode("dataset", io::JsonReader(neither, "run.json")), InputError);
  const nlohmann::json empty = {{"plate", plate}, {"rpim", rpim}, {"datasets", nlohmann::json::object()}};
  EXPECT_THROW(run_rpim_mode("dataset", io::JsonReader(empty, "run.json")), InputError);
}
