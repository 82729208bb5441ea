// Levenberg–Marquardt fits with cross-validated orders (002 §2.4, §3): exact recovery of known
// polynomials, agreement with an independent least-squares solve, order choice by
// cross-validation under noise, refusal of ill-posed fits, and a playback that equals the direct
// evaluation of the three relations without allocating.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "softsim/fit/basis.hpp"
#include "softsim/fit/cross_validation.hpp"
#include "softsim/fit/dataset_json.hpp"
#include "softsim/fit/fit_driver.hpp"
#include "softsim/fit/lm_fit.hpp"
#include "softsim/fit/model_json.hpp"
#include "softsim/fit/paper_units.hpp"
#include "softsim/fit/playback.hpp"
#include "softsim/fit/relations.hpp"
#include "softsim/fit/static_series.hpp"
#include "softsim/fit/superposition.hpp"
#include "softsim/io/artifact.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/mesh/cuboid.hpp"
#include "softsim/io/errors.hpp"

#include "support/scenes.hpp"

// ---- counting every heap allocation of this process (glibc: malloc is interposable) ----
// Not under sanitizers, which bring their own allocator.
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || __has_feature(thread_sanitizer)
#define SOFTSIM_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SOFTSIM_SANITIZED 1
#endif
#if defined(__GLIBC__) && !defined(SOFTSIM_SANITIZED)
extern "C" void* __libc_malloc(std::size_t);
namespace {
bool g_count_allocations = false;
long g_allocations = 0;
}  // namespace
extern "C" void* malloc(std::size_t n) {
  if (g_count_allocations) ++g_allocations;
  return __libc_malloc(n);
}
#define SOFTSIM_COUNTS_ALLOCATIONS 1
#endif

using namespace softsim;
using namespace softsim::fit;

namespace {

// ---------- a synthetic plate: 11 × 11 top nodes, 48 mm square, loaded node 61 ----------
constexpr int kSide = 11;
constexpr double kSpacing = 0.0048;

Eigen::MatrixXd plate_nodes() {
  Eigen::MatrixXd nodes(kSide * kSide, 3);
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) nodes.row(i + kSide * j) << i * kSpacing, j * kSpacing, 0.006;
  return nodes;
}

// Response to a unit force along d (m per N): separable polynomials of known orders in
// s = x / 48 mm, t = y / 48 mm, different for every (d, c).
double unit_field(int d, int c, double x, double y) {
  const double s = x / 0.048, t = y / 0.048;
  const double amp = 1e-3 * (1.0 + d + 0.5 * c);
  switch ((d * 3 + c) % 3) {
    case 0: return amp * (0.3 - 1.2 * s + 2.0 * s * s - 0.7 * s * s * s + 0.4 * t - 0.9 * t * t);  // (3, 2)
    case 1: return amp * (-0.1 + 0.8 * s * s - 0.5 * t + 1.5 * t * t * t - 0.6 * t * t * t * t);  // (2, 4)
    default: return amp * (0.2 + 0.5 * s - 0.3 * t + 0.9 * t * t);                               // (1, 2)
  }
}
// The true separable orders of unit_field(d, c).
std::array<int, 2> unit_field_orders(int d, int c) {
  switch ((d * 3 + c) % 3) {
    case 0: return {3, 2};
    case 1: return {2, 4};
    default: return {1, 2};
  }
}

// A linear body: displacement = Σ_d F_d U_d.
Eigen::MatrixXd linear_response(const Eigen::MatrixXd& nodes, const Eigen::Vector3d& f) {
  Eigen::MatrixXd u = Eigen::MatrixXd::Zero(nodes.rows(), 3);
  for (Eigen::Index j = 0; j < nodes.rows(); ++j)
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) u(j, c) += f[d] * unit_field(d, c, nodes(j, 0), nodes(j, 1));
  return u;
}

Eigen::MatrixXd unit_solutions(const Eigen::MatrixXd& nodes) {
  Eigen::MatrixXd u(3 * nodes.rows(), 3);
  for (Eigen::Index j = 0; j < nodes.rows(); ++j)
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) u(3 * j + c, d) = unit_field(d, c, nodes(j, 0), nodes(j, 1));
  return u;
}

Dataset axis_dataset(int d, int cases) {
  Dataset ds;
  ds.source = std::string("synthetic_axis_") + "xyz"[d];
  ds.kind = std::string("axis_") + "xyz"[d];
  ds.nodes = plate_nodes();
  ds.loaded_node = 60;
  for (int i = 1; i <= cases; ++i) {
    LoadCase lc;
    lc.force[d] = static_cast<double>(i) / cases;
    lc.displacement = linear_response(ds.nodes, lc.force);
    ds.cases.push_back(lc);
  }
  ds.unit_solutions = unit_solutions(ds.nodes);
  return ds;
}

FitSettings small_settings() {
  FitSettings s;
  s.limits.force = 3;
  s.limits.surface_x = 4;
  s.limits.surface_y = 4;
  s.limits.bivariate = 4;
  s.limits.parameter = 2;
  return s;
}

std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = a + (b - a) * i / (n - 1);
  return v;
}

}  // namespace

// ---------------------------------------------------------------- basis

TEST(Basis, LegendreRecurrenceMatchesClosedForms) {
  double p[5];
  for (double t : {-1.0, -0.3, 0.0, 0.55, 1.0}) {
    evaluate_basis(Basis::legendre, 4, t, p);
    EXPECT_DOUBLE_EQ(p[2], 0.5 * (3 * t * t - 1));
    EXPECT_NEAR(p[3], 0.5 * (5 * t * t * t - 3 * t), 1e-15);
    EXPECT_NEAR(p[4], (35 * std::pow(t, 4) - 30 * t * t + 3) / 8, 1e-15);
  }
}

TEST(Basis, MonomialConversionReproducesThePolynomial) {
  // p(x) in the scaled Legendre basis equals Σ m_k u^k with x = origin + u / unit.
  Polynomial1D p;
  p.basis = Basis::legendre;
  p.scale = AffineScale::from_range(0.01, 0.05);
  p.coefficients.resize(6);
  p.coefficients << 0.3, -1.1, 0.7, 0.25, -0.4, 0.05;
  const double origin = 0.002, unit = 1000.0;
  const Eigen::VectorXd m = basis_to_monomial(p.basis, p.scale, 5, origin, unit) * p.coefficients;
  for (double x : {0.01, 0.023, 0.04, 0.05}) {
    const double u = (x - origin) * unit;
    double mono = 0.0;
    for (int k = 5; k >= 0; --k) mono = mono * u + m[k];
    EXPECT_NEAR(mono, p(x), 1e-12);
  }
}

// ---------------------------------------------------------------- Levenberg–Marquardt

TEST(LevenbergMarquardt, RecoversPolynomialCoefficientsExactlyFromNoiseFreeData) {
  // δ = 0.8e-3 − 14.5e-3 F + 2e-3 F² − 3e-3 F³ (m, N): noise-free samples over 0..1 N.
  const Eigen::Vector4d truth(0.8e-3, -14.5e-3, 2e-3, -3e-3);
  const std::vector<double> F = linspace(0.0, 1.0, 12);
  std::vector<double> delta;
  for (double f : F) delta.push_back(truth[0] + f * (truth[1] + f * (truth[2] + f * truth[3])));
  FitOptions opt;
  opt.lm.record_history = true;
  const AffineScale scale = input_scale(F, true);
  const LinearFit fit = fit_polynomial(F, delta, 3, scale, opt);
  ASSERT_TRUE(fit.ok()) << fit.message;
  const Eigen::VectorXd mono = basis_to_monomial(Basis::legendre, scale, 3, 0.0, 1.0) * fit.coefficients;
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(mono[k], truth[k], 1e-12 * truth.cwiseAbs().maxCoeff()) << "k = " << k;
  // 002 eqs. 33–37: after every accepted step the damping is lowered.
  ASSERT_GE(fit.history.size(), 2u);
  for (std::size_t i = 1; i < fit.history.size(); ++i)
    if (fit.history[i].accepted) EXPECT_LT(fit.history[i].damping, fit.history[i - 1].damping);
  EXPECT_LT(fit.final_cost, 1e-24 * fit.initial_cost + 1e-40);
}

TEST(LevenbergMarquardt, AgreesWithAnIndependentLeastSquaresSolveOnNoisyData) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  const std::vector<double> x = linspace(-2.0, 3.0, 40);
  std::vector<double> y;
  for (double v : x) y.push_back(1.0 + 0.5 * v - 0.2 * v * v + noise(rng));
  FitOptions opt;
  const AffineScale scale = input_scale(x, true);
  const LinearFit fit = fit_polynomial(x, y, 4, scale, opt);
  ASSERT_TRUE(fit.ok()) << fit.message;
  const Eigen::MatrixXd A = polynomial_design(Basis::legendre, scale, x, 4);
  const Eigen::VectorXd ls = A.colPivHouseholderQr().solve(Eigen::Map<const Eigen::VectorXd>(y.data(), y.size()));
  EXPECT_LT((fit.coefficients - ls).norm(), 1e-10 * ls.norm());
}

TEST(LevenbergMarquardt, RefusesFewerSamplesThanParameters) {
  const std::vector<double> x = {0.0, 0.5, 1.0};
  const std::vector<double> y = {1.0, 2.0, 0.5};
  FitOptions opt;
  const LinearFit fit = fit_polynomial(x, y, 3, input_scale(x, true), opt);
  EXPECT_EQ(fit.status, FitStatus::too_few_samples);
  EXPECT_THROW(require_ok(fit, "relation 1"), NumericalError);
  // In cross-validation the order is flagged, not fitted.
  const CvScore score = cv_polynomial(x, y, 2, input_scale(x, true), opt);
  EXPECT_EQ(score.status, FitStatus::too_few_samples);
}

TEST(LevenbergMarquardt, RefusesIllConditionedDesigns) {
  FitOptions opt;
  // Raw monomials of coordinates in metres (0..48 mm), order 8: cond(AᵀA) far beyond 1e12.
  const std::vector<double> x = linspace(0.0, 0.048, 11);
  std::vector<double> y;
  for (double v : x) y.push_back(std::sin(40.0 * v));
  opt.basis = Basis::monomial;
  const LinearFit raw = fit_polynomial(x, y, 8, input_scale(x, false), opt);
  EXPECT_EQ(raw.status, FitStatus::ill_conditioned);
  EXPECT_GT(raw.condition, opt.lm.max_condition);
  // The same order on the coordinate scaled to [-1, 1] in the Legendre basis is well posed.
  opt.basis = Basis::legendre;
  const LinearFit scaled = fit_polynomial(x, y, 8, input_scale(x, true), opt);
  EXPECT_TRUE(scaled.ok()) << scaled.message;
  EXPECT_LT(scaled.condition, 1e6);
  // A rank-deficient design (every sample at the same x) is singular.
  const std::vector<double> same(6, 0.3);
  const LinearFit singular = fit_polynomial(same, std::vector<double>(6, 1.0), 1, input_scale(same, true), opt);
  EXPECT_EQ(singular.status, FitStatus::ill_conditioned);
  EXPECT_FALSE(std::isfinite(singular.condition));
}

TEST(LevenbergMarquardt, ReportsAFitThatDidNotConverge) {
  const std::vector<double> x = linspace(0.0, 1.0, 10);
  std::vector<double> y;
  for (double v : x) y.push_back(3.0 - 2.0 * v + v * v);
  FitOptions opt;
  opt.lm.max_iterations = 1;
  opt.lm.initial_damping = 1e3;  // a heavily damped first step cannot reach the minimum
  const LinearFit fit = fit_polynomial(x, y, 2, input_scale(x, true), opt);
  EXPECT_EQ(fit.status, FitStatus::not_converged);
  EXPECT_THROW(require_ok(fit, "relation 1"), NumericalError);
}

// ---------------------------------------------------------------- cross-validation

TEST(CrossValidation, FoldsPartitionTheSamplesReproducibly) {
  const std::vector<int> a = assign_folds(23, 5, 42), b = assign_folds(23, 5, 42), c = assign_folds(23, 5, 43);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  std::vector<int> sizes(5, 0);
  for (int f : a) ++sizes.at(f);
  for (int s : sizes) EXPECT_TRUE(s == 4 || s == 5);
  EXPECT_EQ(effective_folds(7, 0), 7);
  EXPECT_EQ(effective_folds(7, 10), 7);
}

TEST(CrossValidation, PicksTheTrueOrderOfANoisyPolynomial) {
  // A cubic force–displacement law (a stiffening body) sampled with 2 % noise.
  std::mt19937_64 rng(3);
  const std::vector<double> F = linspace(0.0, 1.0, 40);
  std::vector<double> delta;
  std::normal_distribution<double> noise(0.0, 0.02);
  for (double f : F) delta.push_back(2.0 * f - 1.5 * f * f * f + noise(rng));
  FitOptions opt;
  opt.folds = 5;
  const AffineScale scale = input_scale(F, true);
  std::vector<CvScore> scores;
  std::vector<int> orders;
  for (int k = 0; k <= 7; ++k) {
    scores.push_back(cv_polynomial(F, delta, k, scale, opt));
    orders.push_back(k);
  }
  const int chosen = select_candidate(scores, orders, Selection::one_standard_error, 0.0);
  EXPECT_EQ(chosen, 3);
  EXPECT_GT(scores[2].mse, 2.0 * scores[3].mse);  // an order too low is clearly worse
}

TEST(CrossValidation, PicksTheTrueSurfaceOrdersUnderNoise) {
  const Eigen::MatrixXd nodes = plate_nodes();
  SurfaceFrame frame;
  frame.x = AffineScale::from_range(0.0, 0.048);
  frame.y = AffineScale::from_range(0.0, 0.048);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 2e-5);
  Eigen::MatrixXd values(nodes.rows(), 3);
  for (int c = 0; c < 3; ++c)
    for (Eigen::Index j = 0; j < nodes.rows(); ++j)
      values(j, c) = (1.0 + 0.5 * c) * unit_field(0, 0, nodes(j, 0), nodes(j, 1)) + noise(rng);  // true (3, 2)
  FitOptions opt;
  std::vector<CvScore> scores;
  std::vector<int> complexity;
  std::vector<SurfaceTerms> terms;
  for (int a = 0; a <= 5; ++a)
    for (int b = 0; b <= 5; ++b) {
      terms.push_back(SurfaceTerms::separable(a, b));
      scores.push_back(cv_surface(terms.back(), frame, nodes, values, opt));
      complexity.push_back(scores.back().parameters);
    }
  const int chosen = select_candidate(scores, complexity, Selection::one_standard_error, 0.0);
  ASSERT_GE(chosen, 0);
  EXPECT_EQ(terms[chosen].order_x, 3);
  EXPECT_EQ(terms[chosen].order_y, 2);
}

TEST(CrossValidation, PrefersBivariateSurfacesWhenTheFieldHasCrossTerms) {
  const Eigen::MatrixXd nodes = plate_nodes();
  SurfaceFrame frame;
  frame.x = AffineScale::from_range(0.0, 0.048);
  frame.y = AffineScale::from_range(0.0, 0.048);
  Eigen::MatrixXd values(nodes.rows(), 1);
  for (Eigen::Index j = 0; j < nodes.rows(); ++j) {
    const double s = nodes(j, 0) / 0.048 - 0.5, t = nodes(j, 1) / 0.048 - 0.5;
    values(j, 0) = 1e-3 * (1.0 - 4.0 * s * s - 4.0 * t * t + 6.0 * s * t);  // a dome with a twist
  }
  FitOptions opt;
  const CvScore separable = cv_surface(SurfaceTerms::separable(4, 4), frame, nodes, values, opt);
  const CvScore bivariate = cv_surface(SurfaceTerms::bivariate(2), frame, nodes, values, opt);
  ASSERT_TRUE(separable.ok() && bivariate.ok());
  EXPECT_LT(bivariate.mse, 1e-20 * separable.mse);  // exact vs. missing the s·t term
}

// ---------------------------------------------------------------- the whole model

// One fit of the synthetic linear plate shared by the tests of this suite.
class LinearPlate : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    data = new std::array<Dataset, 3>;
    for (int d = 0; d < 3; ++d) (*data)[d] = axis_dataset(d, 6);
    result = new FitResult(fit_surface_model({&(*data)[0], &(*data)[1], &(*data)[2]}, small_settings(), false));
  }
  static void TearDownTestSuite() {
    delete result;
    delete data;
  }
  static std::array<Dataset, 3>* data;
  static FitResult* result;
};
std::array<Dataset, 3>* LinearPlate::data = nullptr;
FitResult* LinearPlate::result = nullptr;

TEST_F(LinearPlate, CrossValidationFindsTheExactOrdersOfNoiseFreeData) {
  for (int d = 0; d < 3; ++d) {
    const DirectionModel& dm = result->model.directions[d];
    EXPECT_EQ(dm.force_to_loaded.order(), 1) << "direction " << d;  // a linear body (002 eq. 49)
    for (int c = 0; c < 3; ++c) {
      const ComponentModel& cm = dm.components[c];
      EXPECT_EQ(cm.surface.model, SurfaceModel::separable);
      EXPECT_EQ(cm.surface.order_x, unit_field_orders(d, c)[0]) << d << c;
      EXPECT_EQ(cm.surface.order_y, unit_field_orders(d, c)[1]) << d << c;
      EXPECT_EQ(cm.parameter_order, 1) << d << c;
    }
  }
}

TEST_F(LinearPlate, PlaybackReproducesCompositeForcesOfALinearBody) {
  const SurfacePlayer player(result->model);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::MatrixXd nodes = plate_nodes();
  Eigen::VectorXd out(3 * nodes.rows());
  for (int k = 0; k < 10; ++k) {
    const Eigen::Vector3d f(u(rng), u(rng), u(rng));
    player.play(f, out.data());
    const Eigen::MatrixXd ref = linear_response(nodes, f);
    const double scale = ref.cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < nodes.rows(); ++j)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[3 * j + c], ref(j, c), 1e-9 * scale);
  }
}

TEST_F(LinearPlate, PlaybackEqualsDirectEvaluationOfTheRelations) {
  const SurfacePlayer player(result->model);
  Eigen::VectorXd out(3 * player.node_count());
  for (const Eigen::Vector3d f : {Eigen::Vector3d(0.9, -0.7, -0.22), Eigen::Vector3d(0.0, 0.3, 1.0)}) {
    player.play(f, out.data());
    const Eigen::MatrixXd direct = evaluate_direct(result->model, f);
    const double scale = direct.cwiseAbs().maxCoeff();
    for (int j = 0; j < player.node_count(); ++j)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[3 * j + c], direct(j, c), 1e-13 * scale);
  }
}

TEST_F(LinearPlate, PlaybackDoesNotAllocate) {
#if defined(SOFTSIM_COUNTS_ALLOCATIONS)
  const SurfacePlayer player(result->model);
  Eigen::VectorXd out(3 * player.node_count());
  const Eigen::Vector3d f(0.9, -0.7, -0.22);
  player.play(f, out.data());
  g_allocations = 0;
  g_count_allocations = true;
  for (int k = 0; k < 100; ++k) player.play(f, out.data());
  g_count_allocations = false;
  EXPECT_EQ(g_allocations, 0);
  // The counter does see allocations (the test can fail).
  g_count_allocations = true;
  const Eigen::MatrixXd direct = evaluate_direct(result->model, f);
  g_count_allocations = false;
  EXPECT_GT(g_allocations, 0);
#else
  GTEST_SKIP() << "allocation counting needs glibc's malloc (not available under sanitizers)";
#endif
}

TEST_F(LinearPlate, SuperpositionOfUnitSolutionsIsExact) {
  const Superposition sup(*(*data)[0].unit_solutions);
  const Eigen::MatrixXd nodes = plate_nodes();
  Eigen::VectorXd out(3 * nodes.rows());
  const Eigen::Vector3d f(0.9, -0.7, -0.22);
  sup.apply(f, out.data());
  const Eigen::MatrixXd ref = linear_response(nodes, f);  // fields evaluated at the composite force
  for (Eigen::Index j = 0; j < nodes.rows(); ++j)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[3 * j + c], ref(j, c), 1e-15);
}

TEST_F(LinearPlate, ModelSurvivesItsJsonRoundTrip) {
  const nlohmann::json j = model_to_json(result->model);
  const FitModel back = model_from_json(io::JsonReader(j, "model.json"));
  const SurfacePlayer a(result->model), b(back);
  Eigen::VectorXd ua(3 * a.node_count()), ub(3 * b.node_count());
  const Eigen::Vector3d f(0.4, 0.1, -0.8);
  a.play(f, ua.data());
  b.play(f, ub.data());
  EXPECT_EQ(ua, ub);
}

TEST_F(LinearPlate, PaperUnitCoefficientsEvaluateToTheSameSurface) {
  // Relation 1 in mm/N: δ_z[mm] = r0 + r1 F.
  const Eigen::VectorXd r = force_relation_in_mm(result->model.directions[2]);
  ASSERT_EQ(r.size(), 2);
  EXPECT_NEAR(r[0], 0.0, 1e-12);
  EXPECT_NEAR(r[1], 1000.0 * unit_field(2, 2, 0.024, 0.024), 1e-9);
  // Surface of displacement y under a force along z, from the monomials in mm.
  const PaperSurface ps = surface_in_mm(result->model, 2, 1);
  const double F = 0.7;
  const double delta_mm = 1000.0 * result->model.directions[2].force_to_loaded(F);
  const Eigen::MatrixXd nodes = plate_nodes();
  for (Eigen::Index j = 0; j < nodes.rows(); j += 7) {
    const double xm = nodes(j, 0) * 1000.0, ym = nodes(j, 1) * 1000.0;
    double u_mm = 0.0;
    for (std::size_t t = 0; t < ps.powers.size(); ++t) {
      double p = 0.0;
      for (Eigen::Index q = ps.beta.cols() - 1; q >= 0; --q) p = p * delta_mm + ps.beta(t, q);
      u_mm += p * std::pow(xm, ps.powers[t][0]) * std::pow(ym, ps.powers[t][1]);
    }
    EXPECT_NEAR(u_mm, 1000.0 * F * unit_field(2, 1, nodes(j, 0), nodes(j, 1)), 1e-9);
  }
}

TEST(FitModel, CrossValidationFindsTheOrdersOfANonlinearBody) {
  // A softening body: δ = F + 0.4 F² at the loaded node, and a surface whose shape changes with
  // δ: u_z = δ·U1 + δ²·U2 with U2 = 0 at the loaded node. True orders: relation 1 → 2,
  // relation 3 → 2; surfaces separable (2, 2).
  Dataset ds;
  ds.nodes = plate_nodes();
  ds.loaded_node = 60;
  for (int i = 1; i <= 10; ++i) {
    LoadCase lc;
    lc.force[2] = 0.1 * i;
    const double F = lc.force[2], delta = 1e-3 * (F + 0.4 * F * F);
    lc.displacement = Eigen::MatrixXd::Zero(ds.nodes.rows(), 3);
    for (Eigen::Index j = 0; j < ds.nodes.rows(); ++j) {
      const double s = ds.nodes(j, 0) / 0.048 - 0.5, t = ds.nodes(j, 1) / 0.048 - 0.5;
      lc.displacement(j, 2) = delta * (1.0 - s * s - t * t) + 1e3 * delta * delta * (s + s * s - 0.5 * t * t);
    }
    ds.cases.push_back(lc);
  }
  FitSettings settings = small_settings();
  const FitResult r = fit_surface_model({nullptr, nullptr, &ds}, settings, false);
  const DirectionModel& dm = r.model.directions[2];
  EXPECT_EQ(dm.force_to_loaded.order(), 2);
  EXPECT_EQ(dm.components[2].surface.order_x, 2);
  EXPECT_EQ(dm.components[2].surface.order_y, 2);
  EXPECT_EQ(dm.components[2].parameter_order, 2);
  // And it plays back a force between the samples exactly.
  const double F = 0.55, delta = 1e-3 * (F + 0.4 * F * F);
  const Eigen::MatrixXd u = evaluate_direct(r.model, Eigen::Vector3d(0, 0, F));
  const double s = ds.nodes(3, 0) / 0.048 - 0.5, t = ds.nodes(3, 1) / 0.048 - 0.5;
  EXPECT_NEAR(u(3, 2), delta * (1.0 - s * s - t * t) + 1e3 * delta * delta * (s + s * s - 0.5 * t * t), 1e-12);
}

TEST(FitModel, RefusesTooFewLoadCasesForTheParameterOrder) {
  const Dataset ds = axis_dataset(2, 2);
  FitSettings s = small_settings();
  s.fixed[2].components[2].parameter_order = 2;  // three coefficients from two load cases
  try {
    fit_surface_model({nullptr, nullptr, &ds}, s, false);
    FAIL() << "expected a NumericalError";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("too_few_samples"), std::string::npos) << e.what();
  }
}

TEST(FitModel, RefusesForcesOffTheAxisOfTheirRelation) {
  Dataset ds = axis_dataset(0, 3);
  ds.cases[1].force[2] = 0.1;
  EXPECT_THROW(fit_surface_model({&ds, nullptr, nullptr}, small_settings(), false), InputError);
}

TEST(FitModel, SameSurfaceToleratesRoundingRelativeToTheSurfaceExtentOnly) {
  // A 5 cm surface: a 1e-12 m rounding of one coordinate is the same surface, a 1e-8 m shift or a
  // missing node is not; the tolerance scales with the extent (the same test at 1 km).
  Eigen::MatrixXd a(3, 3);
  a << 0, 0, 0.05, 0.05, 0, 0.05, 0, 0.05, 0.05;
  Eigen::MatrixXd b = a;
  b(1, 0) += 1e-12;
  EXPECT_TRUE(same_surface(a, b));
  b(1, 0) += 1e-8;
  EXPECT_FALSE(same_surface(a, b));
  EXPECT_FALSE(same_surface(a, a.topRows(2)));
  EXPECT_TRUE(same_surface(2e4 * a, 2e4 * a + Eigen::MatrixXd::Constant(3, 3, 1e-7)));
}

TEST(FitModel, RefusesDatasetsOnDifferentSurfaces) {
  Dataset x = axis_dataset(0, 3), y = axis_dataset(1, 3);
  y.nodes(0, 2) += 1e-6;
  EXPECT_THROW(fit_surface_model({&x, &y, nullptr}, small_settings(), false), InputError);
}

TEST(FitModel, ZeroSurfaceIsPlayedAsNoDisplacement) {
  // The paper's choice Δy = 0 under a force along X (Table 1), fixed in the settings.
  const Dataset ds = axis_dataset(0, 4);
  FitSettings s = small_settings();
  s.fixed[0].components[1].surface = SurfaceTerms::zero();
  const FitResult r = fit_surface_model({&ds, nullptr, nullptr}, s, false);
  const SurfacePlayer player(r.model);
  Eigen::VectorXd out(3 * player.node_count());
  player.play(Eigen::Vector3d(0.5, 0.0, 0.0), out.data());
  for (int j = 0; j < player.node_count(); ++j) EXPECT_EQ(out[3 * j + 1], 0.0);
}

TEST(FitModel, LoadedNodeTakesTheDisplacementOfRelationOne) {
  // A point load makes a peak at the loaded node that low-order surfaces smooth out; 002 §5.1.1
  // substitutes eq. 49 there. Data: a smooth bowl plus a sharp peak at node 61, force along z.
  Dataset ds;
  ds.nodes = plate_nodes();
  ds.loaded_node = 60;
  for (int i = 1; i <= 5; ++i) {
    LoadCase lc;
    lc.force[2] = 0.2 * i;
    lc.displacement = Eigen::MatrixXd::Zero(ds.nodes.rows(), 3);
    for (Eigen::Index j = 0; j < ds.nodes.rows(); ++j) {
      const double s = ds.nodes(j, 0) / 0.048 - 0.5, t = ds.nodes(j, 1) / 0.048 - 0.5;
      lc.displacement(j, 2) = -6e-3 * lc.force[2] * ((1 - 4 * s * s) * (1 - 4 * t * t) + (j == 60 ? 0.3 : 0.0));
    }
    ds.cases.push_back(lc);
  }
  FitSettings s = small_settings();
  s.fixed[2].components[2].surface = SurfaceTerms::separable(2, 2);
  const double truth = ds.cases[2].displacement(60, 2);  // F = 0.6 N
  const Eigen::Vector3d f(0.0, 0.0, 0.6);
  Eigen::VectorXd out(3 * ds.node_count());
  s.loaded_node_from_relation1 = true;
  const FitResult with = fit_surface_model({nullptr, nullptr, &ds}, s, false);
  SurfacePlayer(with.model).play(f, out.data());
  EXPECT_NEAR(out[3 * 60 + 2], truth, 1e-12 * std::abs(truth));
  EXPECT_NEAR(evaluate_direct(with.model, f)(60, 2), truth, 1e-12 * std::abs(truth));
  s.loaded_node_from_relation1 = false;
  const FitResult without = fit_surface_model({nullptr, nullptr, &ds}, s, false);
  SurfacePlayer(without.model).play(f, out.data());
  EXPECT_GT(std::abs(out[3 * 60 + 2] - truth), 0.1 * std::abs(truth));
}

// ---------------------------------------------------------------- dataset artifact

TEST(DatasetJson, ReadsTheRpimDatasetPayloadAndChecksIt) {
  nlohmann::json nodes = nlohmann::json::array(), disp = nlohmann::json::array();
  for (int j = 0; j < 4; ++j) {
    nodes.push_back({0.01 * j, 0.0, 0.006});
    disp.push_back({0.0, 0.0, -1e-3 * j});
  }
  nlohmann::json payload = {{"dataset", {{"kind", "axis_z"}, {"count", 1}, {"seed", nullptr}}},
                            {"plate", {{"size", {0.048, 0.048, 0.006}}}},
                            {"loaded_node", 2},
                            {"top_nodes", nodes},
                            {"cases", {{{"force", {0.0, 0.0, -0.5}}, {"top_displacement", disp}}}},
                            {"unit_solutions", {disp, disp, disp}}};
  const Dataset ds = dataset_from_json(io::JsonReader(payload, "d.json", "/payload"), "d.json");
  EXPECT_EQ(ds.loaded_node, 1);
  EXPECT_EQ(ds.case_count(), 1);
  EXPECT_DOUBLE_EQ(ds.cases[0].displacement(3, 2), -3e-3);
  ASSERT_TRUE(ds.unit_solutions.has_value());
  EXPECT_DOUBLE_EQ((*ds.unit_solutions)(3 * 2 + 2, 1), -2e-3);

  payload["dataset"]["count"] = 2;
  try {
    dataset_from_json(io::JsonReader(payload, "d.json", "/payload"), "d.json");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("d.json: /payload/dataset/count"), std::string::npos) << e.what();
  }
}

// A member of an rpim_dataset_set reads exactly as the same payload in its own rpim_dataset;
// a missing member, or a reference of the wrong shape, is bad input naming what was expected.
TEST(DatasetJson, AMemberOfADatasetSetReadsLikeItsOwnArtifact) {
  nlohmann::json nodes = nlohmann::json::array(), disp = nlohmann::json::array();
  for (int j = 0; j < 4; ++j) {
    nodes.push_back({0.01 * j, 0.0, 0.006});
    disp.push_back({1e-4 * j, 0.0, -1e-3 * j});
  }
  const nlohmann::json payload = {{"dataset", {{"kind", "axis_z"}, {"count", 1}, {"seed", nullptr}}},
                                  {"loaded_node", 2},
                                  {"top_nodes", nodes},
                                  {"cases", {{{"force", {0.0, 0.0, -0.5}}, {"top_displacement", disp}}}},
                                  {"unit_solutions", {disp, disp, disp}}};
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "softsim_test_fit_set";
  std::filesystem::create_directories(dir);
  const std::string single = (dir / "single.json").string(), set = (dir / "set.json").string();
  io::write_artifact(single, kDatasetSchema, kDatasetSchemaVersion, io::Provenance{}, payload);
  io::write_artifact(set, kDatasetSetSchema, kDatasetSetSchemaVersion, io::Provenance{},
                     {{"members", {{"z", payload}}}, {"timing", {{"total_s", 0.1}}}});
  const Dataset a = read_dataset(single);
  const nlohmann::json ref_json = {{"artifact", set}, {"member", "z"}};
  const DatasetRef ref = dataset_ref_from_json(io::JsonReader(ref_json, "fit.json", "/datasets/z"));
  EXPECT_EQ(ref.path, set);
  EXPECT_EQ(ref.member, "z");
  const Dataset b = read_dataset(ref);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.loaded_node, b.loaded_node);
  ASSERT_EQ(a.case_count(), b.case_count());
  EXPECT_EQ(a.cases[0].displacement, b.cases[0].displacement);
  EXPECT_EQ(*a.unit_solutions, *b.unit_solutions);
  // A plain string is the whole artifact, as before.
  const nlohmann::json plain = single;
  EXPECT_TRUE(dataset_ref_from_json(io::JsonReader(plain, "fit.json", "/datasets/z")).member.empty());
  try {
    read_dataset(DatasetRef{set, "x"});
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/payload/members"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("\"x\""), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_dataset(DatasetRef{single, "z"}), InputError);  // not a set
  const nlohmann::json no_member = {{"artifact", set}};
  EXPECT_THROW(dataset_ref_from_json(io::JsonReader(no_member, "fit.json", "/datasets/z")), InputError);
  const nlohmann::json extra = {{"artifact", set}, {"member", "z"}, {"other", 1}};
  EXPECT_THROW(dataset_ref_from_json(io::JsonReader(extra, "fit.json", "/datasets/z")), InputError);
  std::filesystem::remove_all(dir);
}

TEST(StaticSeries, TakesTheTopFaceInGridOrderAndTheNearestLoadedNode) {
  // A 4 × 4 × 2 cuboid; each "solution" displaces node i by (i, 2 i, −3 i) µm.
  const mesh::TetMesh m = test_scenes::cuboid(4, 4, 2, 0.04, 0.04, 0.02);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "softsim_test_fit_series";
  std::filesystem::create_directories(dir);
  const std::string mesh_path = (dir / "mesh.json").string();
  io::write_artifact(mesh_path, io::kMeshSchema, io::kMeshSchemaVersion, io::Provenance{}, io::mesh_to_json(m));
  StaticSeries s;
  s.mesh = mesh_path;
  s.loaded_point = Eigen::Vector3d(0.021, 0.019, 0.02);
  for (int k = 1; k <= 2; ++k) {
    nlohmann::json disp = nlohmann::json::array();
    for (int i = 0; i < m.num_nodes(); ++i) disp.push_back({1e-6 * k * i, 2e-6 * k * i, -3e-6 * k * i});
    const std::string path = (dir / ("result" + std::to_string(k) + ".json")).string();
    io::write_artifact(path, "dhd_result", 1, io::Provenance{}, {{"displacement", disp}});
    s.cases.push_back({path, Eigen::Vector3d(0.0, 0.0, -0.5 * k)});
  }
  const Dataset ds = read_static_series(s);
  ASSERT_EQ(ds.node_count(), 25);
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) {
      EXPECT_NEAR(ds.nodes(i + 5 * j, 0), 0.01 * i, 1e-12);
      EXPECT_NEAR(ds.nodes(i + 5 * j, 1), 0.01 * j, 1e-12);
      EXPECT_NEAR(ds.nodes(i + 5 * j, 2), 0.02, 1e-12);
    }
  EXPECT_EQ(ds.loaded_node, 12);  // the centre of the top face
  // Each surface row carries the displacement of its own mesh node.
  for (int j = 0; j < ds.node_count(); ++j) {
    int mesh_node = -1;
    for (int i = 0; i < m.num_nodes(); ++i)
      if ((m.nodes[i] - ds.nodes.row(j).transpose()).norm() < 1e-12) mesh_node = i;
    ASSERT_GE(mesh_node, 0);
    EXPECT_DOUBLE_EQ(ds.cases[1].displacement(j, 2), -6e-6 * mesh_node);
  }
  EXPECT_DOUBLE_EQ(ds.cases[1].force[2], -1.0);
  s.surface_set = "no_such_set";
  EXPECT_THROW(read_static_series(s), InputError);
  std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------- trivariate surfaces

namespace {

// Nodes on a closed, bumpy surface around (0.1, 0.05, 0.02) m, about 60 mm across: every (x, y)
// inside is covered by an upper and a lower node, as on an organ. The radius varies with both
// angles so that the nodes lie on no low-degree algebraic surface (on a sphere, x² + y² + z² is
// constant and a trivariate design of degree ≥ 2 would be singular).
Eigen::MatrixXd closed_surface_nodes() {
  constexpr int kRings = 14, kPerRing = 20;
  Eigen::MatrixXd nodes(kRings * kPerRing + 2, 3);
  const Eigen::Vector3d centre(0.1, 0.05, 0.02);
  int r = 0;
  auto put = [&](double theta, double phi) {
    const double rho = 0.03 * (1.0 + 0.25 * std::cos(3.0 * theta) * std::sin(2.0 * phi) + 0.15 * std::cos(5.0 * phi));
    nodes.row(r++) = centre + rho * Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                                     0.6 * std::cos(theta));
  };
  put(0.0, 0.0);
  put(M_PI, 0.0);
  for (int i = 1; i <= kRings; ++i)
    for (int k = 0; k < kPerRing; ++k) put(M_PI * i / (kRings + 1), 2.0 * M_PI * (k + 0.5 * (i % 2)) / kPerRing);
  return nodes;
}

// Response to a unit force along d (m per N): trivariate polynomials of total degree 3 (m/N) in
// the coordinates relative to the centre, in units of 30 mm, with x–z, y–z and z³ terms, so
// that the upper and lower nodes over one (x, y) move differently.
double organ_field(int d, int c, double x, double y, double z) {
  const double s = (x - 0.1) / 0.03, t = (y - 0.05) / 0.03, w = (z - 0.02) / 0.03;
  const double amp = 1e-3 * (1.0 + d + 0.5 * c);
  return amp * (0.2 - 0.4 * s + 0.3 * w + 0.5 * s * w - 0.6 * t * w + 0.2 * w * w * w - 0.3 * s * s * t +
                0.1 * (d - c) * t * t * w);
}

Dataset organ_dataset(int d, int cases) {
  Dataset ds;
  ds.source = std::string("synthetic_organ_") + "xyz"[d];
  ds.kind = std::string("axis_") + "xyz"[d];
  ds.nodes = closed_surface_nodes();
  ds.loaded_node = 7;
  ds.unit_solutions = Eigen::MatrixXd(3 * ds.nodes.rows(), 3);
  for (Eigen::Index j = 0; j < ds.nodes.rows(); ++j)
    for (int c = 0; c < 3; ++c)
      for (int e = 0; e < 3; ++e)
        (*ds.unit_solutions)(3 * j + c, e) = organ_field(e, c, ds.nodes(j, 0), ds.nodes(j, 1), ds.nodes(j, 2));
  for (int i = 1; i <= cases; ++i) {
    LoadCase lc;
    lc.force[d] = static_cast<double>(i) / cases;
    lc.displacement = Eigen::MatrixXd(ds.nodes.rows(), 3);
    for (Eigen::Index j = 0; j < ds.nodes.rows(); ++j)
      for (int c = 0; c < 3; ++c) lc.displacement(j, c) = lc.force[d] * (*ds.unit_solutions)(3 * j + c, d);
    ds.cases.push_back(lc);
  }
  return ds;
}

SurfaceFrame organ_frame(const Eigen::MatrixXd& nodes) {
  SurfaceFrame frame;
  frame.x = AffineScale::from_range(nodes.col(0).minCoeff(), nodes.col(0).maxCoeff());
  frame.y = AffineScale::from_range(nodes.col(1).minCoeff(), nodes.col(1).maxCoeff());
  frame.z = AffineScale::from_range(nodes.col(2).minCoeff(), nodes.col(2).maxCoeff());
  return frame;
}

}  // namespace

TEST(TrivariateSurface, TermsAreTheFullTrivariateBasisWithTheBivariateOnesFirstInEachDegree) {
  const SurfaceTerms t = SurfaceTerms::trivariate(4, 4);
  EXPECT_EQ(t.size(), 35);  // C(4 + 3, 3)
  const SurfaceTerms flat = SurfaceTerms::trivariate(4, 0);
  const SurfaceTerms biv = SurfaceTerms::bivariate(4);
  ASSERT_EQ(flat.size(), biv.size());
  for (int k = 0; k < biv.size(); ++k) EXPECT_EQ(flat.terms[k], biv.terms[k]) << "term " << k;
  EXPECT_FALSE(flat.uses_z());
  EXPECT_TRUE(t.uses_z());
}

TEST(TrivariateSurface, LevenbergMarquardtRecoversAKnownPolynomialExactly) {
  const Eigen::MatrixXd nodes = closed_surface_nodes();
  ASSERT_TRUE(nodes_span_z(nodes));
  const SurfaceFrame frame = organ_frame(nodes);
  Eigen::MatrixXd values(nodes.rows(), 2);
  for (Eigen::Index j = 0; j < nodes.rows(); ++j)
    for (int c = 0; c < 2; ++c) values(j, c) = organ_field(c, 2, nodes(j, 0), nodes(j, 1), nodes(j, 2));
  FitOptions opt;
  FitSummary summary;
  const SurfaceTerms terms = SurfaceTerms::trivariate(3, 3);
  const Eigen::MatrixXd coef = fit_surfaces(terms, frame, nodes, values, opt, "trivariate", &summary);
  EXPECT_EQ(summary.parameters, 20);
  EXPECT_LT(summary.condition, 1e8);
  // The fitted polynomial is the true one everywhere, not only at the nodes: compare inside the box.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd probe(50, 3);
  for (Eigen::Index r = 0; r < probe.rows(); ++r)
    probe.row(r) << 0.1 + 0.03 * u(rng), 0.05 + 0.03 * u(rng), 0.02 + 0.02 * u(rng);
  const Eigen::MatrixXd fitted = surface_design(terms, frame, probe) * coef;
  const double scale = values.cwiseAbs().maxCoeff();
  for (Eigen::Index r = 0; r < probe.rows(); ++r)
    for (int c = 0; c < 2; ++c)
      EXPECT_NEAR(fitted(r, c), organ_field(c, 2, probe(r, 0), probe(r, 1), probe(r, 2)), 1e-11 * scale);
  // A surface of x and y alone cannot tell the upper from the lower nodes: even degree 8 misses.
  FitSummary flat;
  fit_surfaces(SurfaceTerms::bivariate(8), frame, nodes, values, opt, "bivariate", &flat);
  EXPECT_GT(flat.rmse, 1e-2 * scale);
}

TEST(TrivariateSurface, OnAPlaneZEqualsConstItIsTheBivariateFit) {
  const Eigen::MatrixXd nodes = plate_nodes();  // every node at z = 6 mm
  ASSERT_FALSE(nodes_span_z(nodes));
  SurfaceFrame frame;
  frame.x = AffineScale::from_range(0.0, 0.048);
  frame.y = AffineScale::from_range(0.0, 0.048);
  frame.z = AffineScale::from_range(0.006, 0.006);
  std::mt19937_64 rng(13);
  std::normal_distribution<double> noise(0.0, 1e-5);
  Eigen::MatrixXd values(nodes.rows(), 2);
  for (Eigen::Index j = 0; j < nodes.rows(); ++j)
    for (int c = 0; c < 2; ++c) values(j, c) = unit_field(1, c, nodes(j, 0), nodes(j, 1)) + noise(rng);
  FitOptions opt;
  for (int n = 0; n <= 6; ++n) {
    const Eigen::MatrixXd tri = fit_surfaces(SurfaceTerms::trivariate(n, 0), frame, nodes, values, opt, "trivariate");
    const Eigen::MatrixXd biv = fit_surfaces(SurfaceTerms::bivariate(n), frame, nodes, values, opt, "bivariate");
    EXPECT_EQ(tri, biv) << "degree " << n;
  }
  // Keeping the z terms there would repeat the constant ones: refused, not silently solved.
  EXPECT_THROW(fit_surfaces(SurfaceTerms::trivariate(2, 2), frame, nodes, values, opt, "trivariate"), NumericalError);
  // The whole fit with surface_model "trivariate" is then the bivariate one.
  std::array<Dataset, 3> data;
  for (int d = 0; d < 3; ++d) data[d] = axis_dataset(d, 6);
  FitSettings tri_settings = small_settings(), biv_settings = small_settings();
  tri_settings.surface_choice = SurfaceChoice::trivariate;
  tri_settings.limits.trivariate = 4;
  biv_settings.surface_choice = SurfaceChoice::bivariate;
  const FitResult tri = fit_surface_model({&data[0], &data[1], &data[2]}, tri_settings, false);
  const FitResult biv = fit_surface_model({&data[0], &data[1], &data[2]}, biv_settings, false);
  for (int d = 0; d < 3; ++d)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(tri.model.directions[d].components[c].surface.degree, biv.model.directions[d].components[c].surface.degree);
      EXPECT_EQ(tri.model.directions[d].components[c].beta, biv.model.directions[d].components[c].beta) << d << c;
    }
}

TEST(TrivariateSurface, FitOfALinearOrganPlaysBackExactlyWithoutAllocating) {
  std::array<Dataset, 3> data;
  for (int d = 0; d < 3; ++d) data[d] = organ_dataset(d, 6);
  FitSettings s = small_settings();
  s.surface_choice = SurfaceChoice::trivariate;
  s.limits.trivariate = 5;
  const FitResult result = fit_surface_model({&data[0], &data[1], &data[2]}, s, false);
  for (int d = 0; d < 3; ++d)
    for (int c = 0; c < 3; ++c) {
      const SurfaceTerms& t = result.model.directions[d].components[c].surface;
      EXPECT_EQ(t.model, SurfaceModel::trivariate);
      EXPECT_EQ(t.degree, 3) << d << c;  // the true degree, chosen by cross-validation
      EXPECT_EQ(t.z_degree, 3) << d << c;
    }
  // Composite forces of the linear body, through the JSON round trip of the model.
  const FitModel model = model_from_json(io::JsonReader(model_to_json(result.model), "model.json"));
  const SurfacePlayer player(model);
  const Eigen::MatrixXd& nodes = data[0].nodes;
  const Eigen::MatrixXd& U = *data[0].unit_solutions;
  Eigen::VectorXd out(3 * player.node_count());
  for (const Eigen::Vector3d f : {Eigen::Vector3d(0.9, -0.7, -0.22), Eigen::Vector3d(0.0, 0.3, 1.0)}) {
    player.play(f, out.data());
    const Eigen::VectorXd exact = U * f;
    const Eigen::MatrixXd direct = evaluate_direct(model, f);
    const double scale = exact.cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < nodes.rows(); ++j)
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(out[3 * j + c], exact[3 * j + c], 1e-9 * scale);
        EXPECT_NEAR(out[3 * j + c], direct(j, c), 1e-13 * scale);
      }
  }
#if defined(SOFTSIM_COUNTS_ALLOCATIONS)
  const Eigen::Vector3d f(0.4, 0.5, -0.6);
  g_allocations = 0;
  g_count_allocations = true;
  for (int k = 0; k < 100; ++k) player.play(f, out.data());
  g_count_allocations = false;
  EXPECT_EQ(g_allocations, 0);
#endif
}
