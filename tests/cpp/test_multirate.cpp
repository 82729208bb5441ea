// Linked asynchronous FEM regions (paper 001): the linear model, the exact reference, the
// three solvers, the asynchronous regions, interpolation and the adaptable primary region.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "softsim/io/errors.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/multirate/async_solver.hpp"
#include "softsim/multirate/bar_model.hpp"
#include "softsim/multirate/comparison.hpp"
#include "softsim/multirate/exact_reference.hpp"
#include "softsim/multirate/force_metrics.hpp"
#include "softsim/multirate/haptic_loop.hpp"
#include "softsim/multirate/region_layout.hpp"
#include "softsim/multirate/run_config.hpp"
#include "softsim/multirate/run_memory.hpp"
#include "softsim/multirate/setup_error.hpp"
#include "softsim/multirate/stability.hpp"
#include "softsim/multirate/whole_model.hpp"

using namespace softsim;
using namespace softsim::multirate;

namespace {

constexpr double kPi = 3.141592653589793;

// Node 0 fixed, a chain of springs `k` with nodal masses `m` (the last may differ).
ReducedSystem chain(const std::vector<double>& k, const std::vector<double>& m, double alpha) {
  LinearModel model;
  model.dofs_per_node = 1;
  const int nodes = static_cast<int>(k.size()) + 1;
  for (int n = 0; n < nodes; ++n) model.positions.emplace_back(n, 0.0, 0.0);
  model.nodal_mass.push_back(1.0);  // fixed node: condensed out
  for (double mi : m) model.nodal_mass.push_back(mi);
  for (int e = 0; e + 1 < nodes; ++e) {
    LinearElement el;
    el.nodes = {e, e + 1};
    el.stiffness.resize(2, 2);
    el.stiffness << k[e], -k[e], -k[e], k[e];
    model.elements.push_back(el);
  }
  model.fixed_nodes = {0};
  ReducedSystem sys = reduce(model);
  set_mass_proportional_damping(sys, alpha);
  return sys;
}

BarSpec soft_bar(int nodes = 40, double E = 5e3) {
  BarSpec b;
  b.nodes = nodes;
  b.length = 0.04;
  b.area = 1e-4;
  b.youngs_modulus = E;
  b.density = 1000.0;
  return b;
}

// The bar with damping ratio `zeta` on its lowest mode; contact = last free node.
ReducedSystem damped_bar(const BarSpec& spec, double zeta) {
  ReducedSystem sys = reduce(make_bar(spec));
  set_mass_proportional_damping(sys, 2.0 * zeta * lowest_natural_frequency(sys));
  return sys;
}

HapticLoopSpec loop_spec(long frames, double ks = 10.0) {
  HapticLoopSpec l;
  l.frame_step = 1e-3;
  l.frames = frames;
  l.probe_stiffness = ks;
  l.direction = Eigen::VectorXd::Ones(1);
  return l;
}

ProbeSignal chirp(double amplitude = 1e-3, double f1 = 5.0, double sweep = 2.0) {
  ProbeSignal s;
  s.kind = ProbeSignal::Kind::kChirp;
  s.amplitude = amplitude;
  s.start_frequency = 0.0;
  s.end_frequency = f1;
  s.sweep_time = sweep;
  return s;
}

ProbeSignal ramp(double amplitude, double start, double ramp_time) {
  ProbeSignal s;
  s.kind = ProbeSignal::Kind::kRampHold;
  s.amplitude = amplitude;
  s.start_time = start;
  s.ramp_time = ramp_time;
  return s;
}

AsyncSpec regions(int primary, std::vector<SecondaryRegionSpec> secondary, const SolverSpec& solver, bool interpolate) {
  AsyncSpec a;
  a.frame_step = 1e-3;
  a.primary.kind = PrimarySizePolicy::Kind::kFixed;
  a.primary.min_nodes = a.primary.max_nodes = primary;
  a.primary_solver = solver;
  for (auto& s : secondary) s.solver = solver;
  a.secondary = std::move(secondary);
  a.interpolate = interpolate;
  return a;
}

SolverSpec solver_of(SolverKind kind, ImplicitScheme scheme = ImplicitScheme::kBackwardEuler,
                     ExplicitVariant variant = ExplicitVariant::kCentral) {
  SolverSpec s;
  s.kind = kind;
  s.implicit_scheme = scheme;
  s.explicit_variant = variant;
  return s;
}

LoopRecord run(FrameStepper& stepper, const ProbeSignal& signal, const HapticLoopSpec& spec) {
  LoopRecord r;
  stepper.reset();
  run_haptic_loop(stepper, signal, spec, r);
  return r;
}

// Exact largest circular frequency of K phi = omega^2 M phi (dense, small systems only).
double exact_omega_max(const ReducedSystem& sys) {
  const Eigen::MatrixXd k = Eigen::MatrixXd(sys.stiffness);
  const Eigen::VectorXd s = sys.mass.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd a = s.asDiagonal() * k * s.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(a);
  return std::sqrt(es.eigenvalues().maxCoeff());
}

}  // namespace

// ---------------------------------------------------------------- the model

TEST(LinearModel, BarTipComplianceIsLOverEA) {
  // A fixed-free bar pulled at its free end: u = F L / (E A), whatever the mesh.
  for (int nodes : {2, 7, 40}) {
    const BarSpec b = soft_bar(nodes);
    const ReducedSystem sys = reduce(make_bar(b));
    const double c = contact_compliance(sys, sys.num_free_nodes() - 1, Eigen::VectorXd::Ones(1));
    EXPECT_NEAR(c, b.length / (b.youngs_modulus * b.area), 1e-12 * c) << nodes << " nodes";
  }
}

TEST(LinearModel, BarLowestFrequencyMatchesDiscreteClosedForm) {
  // A fixed-free lumped chain of M elements (half mass at the free end) is half of a
  // fixed-fixed chain of 2M elements: omega_1 = (2 c / h) sin(pi / (4 M)), and it tends to the
  // continuum's pi c / (2 L) as M grows.
  for (int nodes : {5, 40, 200}) {
    const BarSpec b = soft_bar(nodes);
    const ReducedSystem sys = reduce(make_bar(b));
    const int m = nodes - 1;
    const double h = b.length / m;
    const double c = std::sqrt(b.youngs_modulus / b.density);
    const double expected = 2.0 * c / h * std::sin(kPi / (4.0 * m));
    EXPECT_NEAR(lowest_natural_frequency(sys), expected, 1e-9 * expected) << nodes << " nodes";
    EXPECT_NEAR(expected, kPi * c / (2.0 * b.length), 0.02 * expected);
  }
}

TEST(LinearModel, TheFactorisationOfTheCheckServesTheLaterSolves) {
  // reduce() keeps the LDLT of its positive-definiteness check; the solves with K give the same
  // bits with it as with a factorisation of their own.
  const ReducedSystem sys = damped_bar(soft_bar(40), 0.3);
  ASSERT_TRUE(sys.stiffness_ldlt);
  ReducedSystem uncached = sys;
  uncached.stiffness_ldlt.reset();
  const int contact = sys.num_free_nodes() - 1;
  const Eigen::VectorXd e = Eigen::VectorXd::Ones(1);
  EXPECT_EQ(lowest_natural_frequency(sys), lowest_natural_frequency(uncached));
  EXPECT_EQ(contact_compliance(sys, contact, e), contact_compliance(uncached, contact, e));
  // A renumbered system has another K: it factorises its own.
  std::vector<int> order(sys.num_free_nodes());
  for (int k = 0; k < sys.num_free_nodes(); ++k) order[k] = sys.num_free_nodes() - 1 - k;
  EXPECT_FALSE(renumbered(sys, order).stiffness_ldlt);
}

TEST(LinearModel, RigidMotionIsRefused) {
  LinearModel model = make_bar(soft_bar(5));
  model.fixed_nodes.clear();  // nothing holds the bar: K is singular
  EXPECT_THROW(reduce(model), NumericalError);
}

// ---------------------------------------------------------------- the exact reference

TEST(ExactReference, OneDofStepResponseMatchesClosedForm) {
  // m u'' + c u' + k u = F from rest: u = F/k (1 - e^{-z w t} (cos wd t + z w / wd sin wd t)),
  // u' = F/k (w^2 / wd) e^{-z w t} sin wd t.
  const double k = 40.0, m = 0.01, alpha = 12.0, F = 0.3, dt = 1e-3;
  const ReducedSystem sys = chain({k}, {m}, alpha);
  ExactReference exact(sys, 0, dt);
  const double w = std::sqrt(k / m), z = alpha / (2.0 * w), wd = w * std::sqrt(1.0 - z * z);
  const Eigen::VectorXd f = Eigen::VectorXd::Constant(1, F);
  for (int n = 1; n <= 400; ++n) {
    exact.advance(f);
    const double t = n * dt;
    const double decay = std::exp(-z * w * t);
    const double u = F / k * (1.0 - decay * (std::cos(wd * t) + z * w / wd * std::sin(wd * t)));
    const double v = F / k * (w * w / wd) * decay * std::sin(wd * t);
    ASSERT_NEAR(exact.state()[0], u, 1e-12 * F / k) << "frame " << n;
    ASSERT_NEAR(exact.state()[1], v, 1e-12 * F / k * w) << "frame " << n;
  }
}

TEST(ExactReference, OneDofPiecewiseConstantForceIsSuperposedSteps) {
  // A force held over each frame is a sum of steps (f_n - f_{n-1}) starting at t_n.
  const double k = 40.0, m = 0.01, alpha = 5.0, dt = 1e-3;
  const ReducedSystem sys = chain({k}, {m}, alpha);
  ExactReference exact(sys, 0, dt);
  const double w = std::sqrt(k / m), z = alpha / (2.0 * w), wd = w * std::sqrt(1.0 - z * z);
  auto step_response = [&](double t) {
    return t <= 0 ? 0.0 : (1.0 - std::exp(-z * w * t) * (std::cos(wd * t) + z * w / wd * std::sin(wd * t))) / k;
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  std::vector<double> forces(120);
  for (double& x : forces) x = dist(rng);
  Eigen::VectorXd f(1);
  for (std::size_t n = 0; n < forces.size(); ++n) {
    f[0] = forces[n];
    exact.advance(f);
    const double t = (n + 1) * dt;
    double u = 0.0;
    for (std::size_t j = 0; j <= n; ++j) u += (forces[j] - (j ? forces[j - 1] : 0.0)) * step_response(t - j * dt);
    ASSERT_NEAR(exact.state()[0], u, 1e-12 / k) << "frame " << n + 1;
  }
}

TEST(ExactReference, TwoDofMatchesModalSolution) {
  // Two masses on two springs, proportional damping C = alpha M, a constant force on the free
  // end. Modes from the 2x2 problem in closed form, each a damped oscillator.
  const double k1 = 30.0, k2 = 20.0, m1 = 0.02, m2 = 0.01, alpha = 8.0, F = 0.5, dt = 5e-4;
  const ReducedSystem sys = chain({k1, k2}, {m1, m2}, alpha);
  ExactReference exact(sys, 1, dt);
  // det(K - l M) = 0 with K = [[k1 + k2, -k2], [-k2, k2]], M = diag(m1, m2).
  const double a = m1 * m2, b = -((k1 + k2) * m2 + k2 * m1), c = k1 * k2;
  const double disc = std::sqrt(b * b - 4 * a * c);
  const double lambda[2] = {(-b - disc) / (2 * a), (-b + disc) / (2 * a)};
  Eigen::Vector2d phi[2];
  for (int i = 0; i < 2; ++i) {
    phi[i] = Eigen::Vector2d(k2, k1 + k2 - lambda[i] * m1);  // first row of (K - l M) phi = 0
    phi[i] /= std::sqrt(m1 * phi[i][0] * phi[i][0] + m2 * phi[i][1] * phi[i][1]);  // M-normalised
  }
  const Eigen::VectorXd f = Eigen::VectorXd::Constant(1, F);
  for (int n = 1; n <= 600; ++n) {
    exact.advance(f);
    const double t = n * dt;
    Eigen::Vector2d u = Eigen::Vector2d::Zero();
    for (int i = 0; i < 2; ++i) {
      const double w = std::sqrt(lambda[i]), z = alpha / (2 * w), wd = w * std::sqrt(1 - z * z);
      const double q_static = phi[i][1] * F / lambda[i];  // modal force phi^T E F over modal stiffness
      const double q = q_static * (1.0 - std::exp(-z * w * t) * (std::cos(wd * t) + z * w / wd * std::sin(wd * t)));
      u += q * phi[i];
    }
    ASSERT_NEAR(exact.state()[0], u[0], 1e-11 * F / k2) << "frame " << n;
    ASSERT_NEAR(exact.state()[1], u[1], 1e-11 * F / k2) << "frame " << n;
  }
}

TEST(ExactReference, SampledSpringCouplingNeedsDamping) {
  // A probe spring evaluated once per frame and held (001 §3) adds energy: on the undamped
  // bar the exact closed loop has a spectral radius above 1; tissue damping makes it stable.
  const BarSpec b = soft_bar(40);
  const ReducedSystem undamped = damped_bar(b, 0.0);
  const ReducedSystem damped = damped_bar(b, 0.3);
  const int contact = undamped.num_free_nodes() - 1;
  EXPECT_GT(ExactReference(undamped, contact, 1e-3).loop_spectral_radius(10.0), 1.0);
  EXPECT_LT(ExactReference(damped, contact, 1e-3).loop_spectral_radius(10.0), 1.0);
}

// ---------------------------------------------------------------- solvers

namespace {

// Contact displacement after `time` under a constant contact force, frame step dt.
double constant_force_response(const ReducedSystem& sys, const SolverSpec& solver, double dt, double time) {
  const int contact = sys.num_free_nodes() - 1;
  WholeModel whole(sys, contact, solver, dt, LinearSolverKind::kSparse);
  const Eigen::VectorXd f = Eigen::VectorXd::Constant(1, 1e-3);
  const long steps = std::lround(time / dt);
  for (long n = 0; n < steps; ++n) whole.advance(f);
  return whole.contact_displacement(0);
}

double exact_constant_force_response(const ReducedSystem& sys, double time) {
  ExactReference exact(sys, sys.num_free_nodes() - 1, time);  // one frame of the whole length
  exact.advance(Eigen::VectorXd::Constant(1, 1e-3));
  return exact.contact_displacement(0);
}

}  // namespace

TEST(Solvers, ConvergeToExactSolutionAtTheirOrder) {
  // Halving the step divides the error by 2^order: backward Euler 1, Newmark average
  // acceleration 2, central differences 2 (constant load, so no sampling effect).
  const ReducedSystem sys = damped_bar(soft_bar(12), 0.3);
  const double T = 0.03;
  const double exact = exact_constant_force_response(sys, T);
  struct Case {
    SolverSpec solver;
    double order;
    double dt;
  };
  const std::vector<Case> cases = {
      {solver_of(SolverKind::kImplicit, ImplicitScheme::kBackwardEuler), 1.0, 2e-4},
      {solver_of(SolverKind::kImplicit, ImplicitScheme::kNewmark), 2.0, 2e-4},
      {solver_of(SolverKind::kExplicit, ImplicitScheme::kNewmark, ExplicitVariant::kCentral), 2.0, 2e-4},
      {solver_of(SolverKind::kExplicit, ImplicitScheme::kNewmark, ExplicitVariant::kBackwardDamping), 1.0, 2e-4},
  };
  for (const Case& c : cases) {
    const double e1 = std::abs(constant_force_response(sys, c.solver, c.dt, T) - exact);
    const double e2 = std::abs(constant_force_response(sys, c.solver, c.dt / 2, T) - exact);
    const double e3 = std::abs(constant_force_response(sys, c.solver, c.dt / 4, T) - exact);
    const double observed = std::log2(std::sqrt(e1 / e3));  // averaged over two halvings
    EXPECT_NEAR(observed, c.order, 0.25) << solver_name(c.solver) << " errors " << e1 << " " << e2 << " " << e3;
  }
}

TEST(Solvers, StaticSolverGivesTheStaticSolution) {
  const BarSpec b = soft_bar(10);
  const ReducedSystem sys = damped_bar(b, 0.3);
  WholeModel whole(sys, sys.num_free_nodes() - 1, solver_of(SolverKind::kStatic), 1e-3, LinearSolverKind::kDense);
  whole.advance(Eigen::VectorXd::Constant(1, 2e-3));
  EXPECT_NEAR(whole.contact_displacement(0), 2e-3 * b.length / (b.youngs_modulus * b.area), 1e-15);
}

TEST(Solvers, DenseAndSparseFactorisationsAgree) {
  const ReducedSystem sys = damped_bar(soft_bar(40), 0.3);
  const int contact = sys.num_free_nodes() - 1;
  WholeModel sparse(sys, contact, solver_of(SolverKind::kImplicit), 1e-3, LinearSolverKind::kSparse);
  WholeModel dense(sys, contact, solver_of(SolverKind::kImplicit), 1e-3, LinearSolverKind::kDense);
  const LoopRecord a = run(sparse, chirp(), loop_spec(2000));
  const LoopRecord b = run(dense, chirp(), loop_spec(2000));
  EXPECT_LT(force_error(a.force, b.force).peak_relative, 1e-12);
}

// ---------------------------------------------------------------- explicit stability limit

TEST(ExplicitLimit, GershgorinBoundIsExactForOneDofAndAboveTheTrueFrequency) {
  const ReducedSystem one = chain({40.0}, {0.01}, 0.0);
  EXPECT_NEAR(omega_max_bound(one, 0, 1), std::sqrt(4000.0), 1e-9);
  const ReducedSystem bar = damped_bar(soft_bar(40), 0.3);
  const double exact = exact_omega_max(bar);
  const double bound = omega_max_bound(bar, 0, bar.num_dofs());
  EXPECT_GE(bound, exact);
  // 001 eq. 4 for the uniform bar, h / c, is 2 / omega of the interior stencil 2 c / h.
  const BarSpec b = soft_bar(40);
  const double h = b.length / 39, c = std::sqrt(b.youngs_modulus / b.density);
  EXPECT_LE(exact, 2.0 * c / h);
}

TEST(ExplicitLimit, StepAboveTheLimitIsRefused) {
  const ReducedSystem sys = damped_bar(soft_bar(40), 0.3);
  const int contact = sys.num_free_nodes() - 1;
  for (ExplicitVariant variant : {ExplicitVariant::kCentral, ExplicitVariant::kBackwardDamping}) {
    const SolverSpec s = solver_of(SolverKind::kExplicit, ImplicitScheme::kNewmark, variant);
    const double limit = explicit_step_limit(sys, 0, sys.num_dofs(), variant);
    EXPECT_THROW(WholeModel(sys, contact, s, 1.01 * limit, LinearSolverKind::kSparse), InputError);
    EXPECT_NO_THROW(WholeModel(sys, contact, s, 0.99 * limit, LinearSolverKind::kSparse));
    // At the haptic rate (1 ms) this bar is far too fine for an explicit solver.
    EXPECT_THROW(WholeModel(sys, contact, s, 1e-3, LinearSolverKind::kSparse), InputError);
  }
  // The same check guards each region at its own step: explicit secondary every 20 frames.
  AsyncSpec a = regions(5, {{0, 20, {}}}, solver_of(SolverKind::kImplicit), true);
  a.secondary[0].solver = solver_of(SolverKind::kExplicit);
  EXPECT_THROW(AsyncSolver(sys, contact, a), InputError);
}

TEST(ExplicitLimit, TheLimitIsRealStableBelowDivergentAbove) {
  // With the check off: just below the enforced limit the bar stays bounded for 20000 steps;
  // just above the true limit (from the exact omega_max) it blows up.
  const ReducedSystem sys = damped_bar(soft_bar(20), 0.05);
  const int contact = sys.num_free_nodes() - 1;
  const double omega = exact_omega_max(sys);
  const double alpha = sys.damping[0] / sys.mass[0];
  for (ExplicitVariant variant : {ExplicitVariant::kCentral, ExplicitVariant::kBackwardDamping}) {
    const SolverSpec s = solver_of(SolverKind::kExplicit, ImplicitScheme::kNewmark, variant);
    const double enforced = explicit_step_limit(sys, 0, sys.num_dofs(), variant);
    const double true_limit = explicit_step_limit(omega, alpha, variant);
    ASSERT_LE(enforced, true_limit);
    const Eigen::VectorXd f = Eigen::VectorXd::Constant(1, 1e-3);
    WholeModel below(sys, contact, s, 0.999 * enforced, LinearSolverKind::kSparse, false);
    double worst = 0.0;
    for (int n = 0; n < 20000; ++n) {
      below.advance(f);
      worst = std::max(worst, std::abs(below.contact_displacement(0)));
    }
    const double static_u = contact_compliance(sys, contact, Eigen::VectorXd::Ones(1)) * 1e-3;
    EXPECT_LT(worst, 3.0 * static_u) << solver_name(s);
    WholeModel above(sys, contact, s, 1.02 * true_limit, LinearSolverKind::kSparse, false);
    worst = 0.0;
    for (int n = 0; n < 20000 && std::isfinite(worst); ++n) {
      above.advance(f);
      worst = std::max(worst, std::abs(above.contact_displacement(0)));
      if (worst > 1e6 * static_u) break;
    }
    EXPECT_GT(worst, 1e6 * static_u) << solver_name(s);
  }
}

// ---------------------------------------------------------------- asynchronous regions

TEST(AsyncRegions, EveryRegionAtFullRateIsTheWholeModel) {
  // Regions solved every frame with the primary's solver form one solve of 001 eq. 7 over all
  // nodes: the same force as the whole model to round-off, for every solver.
  const ReducedSystem soft = damped_bar(soft_bar(40), 0.3);
  const ReducedSystem coarse = damped_bar(soft_bar(12, 2e3), 0.3);  // explicit-stable at 1 kHz
  struct Case {
    const ReducedSystem* sys;
    SolverSpec solver;
    double ks;
  };
  const std::vector<Case> cases = {
      {&soft, solver_of(SolverKind::kImplicit, ImplicitScheme::kBackwardEuler), 10.0},
      {&soft, solver_of(SolverKind::kImplicit, ImplicitScheme::kNewmark), 10.0},
      {&soft, solver_of(SolverKind::kStatic), 5.0},
      {&coarse, solver_of(SolverKind::kExplicit, ImplicitScheme::kNewmark, ExplicitVariant::kCentral), 2.0},
      {&coarse, solver_of(SolverKind::kExplicit, ImplicitScheme::kNewmark, ExplicitVariant::kBackwardDamping), 2.0},
  };
  for (const Case& c : cases) {
    const int contact = c.sys->num_free_nodes() - 1;
    WholeModel whole(*c.sys, contact, c.solver, 1e-3, LinearSolverKind::kSparse);
    const LoopRecord ref = run(whole, chirp(), loop_spec(3000, c.ks));
    for (bool interpolate : {true, false}) {
      AsyncSolver async(*c.sys, contact, regions(3, {{4, 1, {}}, {0, 1, {}}}, c.solver, interpolate));
      const LoopRecord got = run(async, chirp(), loop_spec(3000, c.ks));
      EXPECT_LT(force_error(got.force, ref.force).peak_relative, 1e-11) << solver_name(c.solver);
    }
  }
}

TEST(AsyncRegions, StaticRegionsConvergeToTheWholeStaticSolution) {
  // Under a held load, solving regions in turn with 001 eq. 7 is block Gauss-Seidel on K: its
  // fixed point is K u = f. Checks the right-hand side coupling of every region.
  const ReducedSystem sys = damped_bar(soft_bar(12), 0.3);
  const int contact = sys.num_free_nodes() - 1;
  Eigen::VectorXd f_full = Eigen::VectorXd::Zero(sys.num_dofs());
  f_full[contact] = 1e-3;
  Eigen::SparseMatrix<double> k = sys.stiffness;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(k);
  const Eigen::VectorXd expected = ldlt.solve(f_full);
  for (bool interpolate : {true, false}) {
    AsyncSolver async(sys, contact, regions(3, {{3, 2, {}}, {0, 3, {}}}, solver_of(SolverKind::kStatic), interpolate));
    const Eigen::VectorXd f = Eigen::VectorXd::Constant(1, 1e-3);
    for (int n = 0; n < 6000; ++n) async.advance(f);
    Eigen::VectorXd u;
    async.published_displacement(u);
    EXPECT_LT((u - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff()) << interpolate;
  }
}

TEST(AsyncRegions, DynamicRegionsSettleOnTheWholeModelForce) {
  // Ramp and hold: once the transient has decayed, the regions' force equals the whole model's.
  const ReducedSystem sys = damped_bar(soft_bar(12), 0.3);
  const int contact = sys.num_free_nodes() - 1;
  WholeModel whole(sys, contact, solver_of(SolverKind::kImplicit), 1e-3, LinearSolverKind::kSparse);
  const ProbeSignal input = ramp(1e-3, 0.05, 0.2);
  const LoopRecord ref = run(whole, input, loop_spec(6000));
  for (bool interpolate : {true, false}) {
    AsyncSolver async(sys, contact, regions(4, {{0, 10, {}}}, solver_of(SolverKind::kImplicit), interpolate));
    const LoopRecord got = run(async, input, loop_spec(6000));
    EXPECT_NEAR(got.force.back(), ref.force.back(), 1e-9 * std::abs(ref.force.back()));
    EXPECT_GT(force_error(got.force, ref.force).peak_relative, 1e-3);  // but not during the motion
  }
}

TEST(AsyncRegions, LayoutErrorsAreInputErrors) {
  const ReducedSystem sys = damped_bar(soft_bar(12), 0.3);
  const int contact = sys.num_free_nodes() - 1;
  const SolverSpec s = solver_of(SolverKind::kImplicit);
  EXPECT_THROW(AsyncSolver(sys, contact, regions(3, {{4, 10, {}}}, s, true)), InputError);       // 4 nodes uncovered
  EXPECT_THROW(AsyncSolver(sys, contact, regions(3, {{0, 10, {}}, {2, 5, {}}}, s, true)), InputError);  // rest not last
  EXPECT_THROW(AsyncSolver(sys, contact, regions(12, {{0, 10, {}}}, s, true)), InputError);      // nothing left
  EXPECT_NO_THROW(AsyncSolver(sys, contact, regions(11, {}, s, true)));                          // primary = whole
}

TEST(AsyncRegions, BordersFollowTheRegionSizes) {
  RegionBorders borders(12, 3);
  EXPECT_EQ(borders.size_of(4), 4);
  ASSERT_TRUE(borders.fits(4));
  borders.append(4);
  EXPECT_EQ(borders.size_of(0), 5);  // 0: the remaining nodes
  EXPECT_FALSE(borders.fits(6));
  EXPECT_FALSE(borders.fits(0));
  EXPECT_FALSE(borders.complete());
  borders.append(borders.size_of(0));
  EXPECT_TRUE(borders.complete());
  EXPECT_EQ(borders.bounds(), (std::vector<int>{3, 7, 12}));
}

TEST(AsyncRegions, ThreeDofsPerNodeAlongAnAxisBehaveLikeTheBar) {
  // The bar rebuilt with 3 DOFs per node along an oblique axis e (axial stiffness k e e^T plus
  // a lateral stiffness, so the lateral DOFs are supported) and probed along e: the axial
  // motion decouples, so whole model, regions and exact reference give the 1-D forces.
  const BarSpec b = soft_bar(20);
  const LinearModel bar1 = make_bar(b);
  const Eigen::Vector3d e = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  LinearModel bar3;
  bar3.dofs_per_node = 3;
  for (int n = 0; n < b.nodes; ++n) bar3.positions.push_back(bar1.positions[n].x() * e);
  bar3.nodal_mass = bar1.nodal_mass;
  bar3.fixed_nodes = bar1.fixed_nodes;
  for (const LinearElement& el : bar1.elements) {
    const double k = el.stiffness(0, 0);
    const Eigen::Matrix3d s = k * e * e.transpose() + 0.3 * k * (Eigen::Matrix3d::Identity() - e * e.transpose());
    LinearElement el3;
    el3.nodes = el.nodes;
    el3.stiffness.resize(6, 6);
    el3.stiffness << s, -s, -s, s;
    bar3.elements.push_back(el3);
  }
  ReducedSystem sys1 = reduce(bar1), sys3 = reduce(bar3);
  const double alpha = 2.0 * 0.3 * lowest_natural_frequency(sys1);
  set_mass_proportional_damping(sys1, alpha);
  set_mass_proportional_damping(sys3, alpha);
  const int contact = sys1.num_free_nodes() - 1;
  HapticLoopSpec loop1 = loop_spec(2000), loop3 = loop_spec(2000);
  loop3.direction = e;
  const SolverSpec s = solver_of(SolverKind::kImplicit);
  AsyncSpec a = regions(5, {{0, 20, {}}}, s, true);
  a.primary.kind = PrimarySizePolicy::Kind::kLinear;  // also exercises the hand-over of 3-DOF nodes
  a.primary.max_nodes = 12;
  a.primary.gradient = 4.0;
  a.primary.scale = 1e-4;
  WholeModel w1(sys1, contact, s, 1e-3, LinearSolverKind::kSparse), w3(sys3, contact, s, 1e-3, LinearSolverKind::kSparse);
  AsyncSolver a1(sys1, contact, a), a3(sys3, contact, a);
  ExactReference x1(sys1, contact, 1e-3), x3(sys3, contact, 1e-3);
  const ProbeSignal in = chirp();
  EXPECT_LT(force_error(run(w3, in, loop3).force, run(w1, in, loop1).force).peak_relative, 1e-10);
  const LoopRecord r1 = run(a1, in, loop1), r3 = run(a3, in, loop3);
  EXPECT_LT(force_error(r3.force, r1.force).peak_relative, 1e-10);
  EXPECT_EQ(r3.primary_nodes, r1.primary_nodes);
  EXPECT_GT(*std::max_element(r1.primary_nodes.begin(), r1.primary_nodes.end()), 5);
  EXPECT_LT(force_error(run(x3, in, loop3).force, run(x1, in, loop1).force).peak_relative, 1e-9);
}

// ---------------------------------------------------------------- interpolation (001 Fig. 4)

TEST(Interpolation, RemovesTheForceJumpsOfHeldSecondaryValues) {
  // A steady push (ramp) with the secondary region solved every 20th frame, measured inside
  // the ramp (0.4 s to 1 s). The scale is the force change per frame of the whole model, dF.
  // Held secondary values are a wall that moves in steps: at each update the force jumps by
  // more than dF (second difference > dF). Interpolated values move continuously: the force's
  // slope changes by less than 5 % of dF from one frame to the next.
  const ReducedSystem sys = damped_bar(soft_bar(40), 0.3);
  const int contact = sys.num_free_nodes() - 1;
  const ProbeSignal input = ramp(2e-3, 0.1, 1.0);
  const HapticLoopSpec loop = loop_spec(1000);
  WholeModel whole(sys, contact, solver_of(SolverKind::kImplicit), 1e-3, LinearSolverKind::kSparse);
  const LoopRecord ref = run(whole, input, loop);
  double per_frame = 0.0;
  for (std::size_t n = 400; n < 1000; ++n) per_frame = std::max(per_frame, std::abs(ref.force[n] - ref.force[n - 1]));
  const SolverSpec s = solver_of(SolverKind::kImplicit);
  AsyncSolver held(sys, contact, regions(5, {{0, 20, {}}}, s, false));
  AsyncSolver interpolated(sys, contact, regions(5, {{0, 20, {}}}, s, true));
  const double jumps = max_second_difference(run(held, input, loop).force, 400, 1000);
  const double lerp = max_second_difference(run(interpolated, input, loop).force, 400, 1000);
  EXPECT_GT(jumps, per_frame) << "held " << jumps << " per-frame change " << per_frame;
  EXPECT_LT(lerp, 0.05 * per_frame) << "interpolated " << lerp << " per-frame change " << per_frame;
}

// ---------------------------------------------------------------- adaptable primary region

TEST(AdaptablePrimary, LinearFunctionHasGradientMinimumAndMaximum) {
  PrimarySizePolicy p;
  p.kind = PrimarySizePolicy::Kind::kLinear;
  p.min_nodes = 10;
  p.max_nodes = 30;
  p.gradient = 4.0;
  p.scale = 1e-3;
  EXPECT_EQ(linear_primary_size(p, 0.0), 10);
  EXPECT_EQ(linear_primary_size(p, 2.4e-3), 10);  // 9.6 -> 10
  EXPECT_EQ(linear_primary_size(p, 4e-3), 16);
  EXPECT_EQ(linear_primary_size(p, 5.1e-3), 21);  // ceil(20.4)
  EXPECT_EQ(linear_primary_size(p, 1.0), 30);
}

namespace {
// Implicit regions on the 40-node bar: a primary region sized by the linear policy (10 nodes at
// rest, 4 more per node spacing of deformation, at most 30), the rest solved every 20th frame.
AsyncSpec linear_adaptive_primary(const BarSpec& b) {
  AsyncSpec spec = regions(10, {{0, 20, {}}}, solver_of(SolverKind::kImplicit), true);
  spec.primary.kind = PrimarySizePolicy::Kind::kLinear;
  spec.primary.max_nodes = 30;
  spec.primary.gradient = 4.0;
  spec.primary.scale = b.length / 39;
  return spec;
}
}  // namespace

TEST(AdaptablePrimary, SizeFollowsTheDeformation) {
  // Ramp to a held deformation: the primary region starts at its minimum and ends at the
  // size the policy gives for the settled deformation (linear) or at the farthest node
  // displaced more than the threshold (threshold variant).
  const BarSpec b = soft_bar(40);
  const ReducedSystem sys = damped_bar(b, 0.3);
  const int contact = sys.num_free_nodes() - 1;
  const ProbeSignal input = ramp(1e-2, 0.05, 0.3);
  const HapticLoopSpec loop = loop_spec(3000);
  WholeModel whole(sys, contact, solver_of(SolverKind::kImplicit), 1e-3, LinearSolverKind::kSparse);
  run(whole, input, loop);
  const Eigen::VectorXd settled = whole.displacement();  // free node i sits at x = (i + 1) h

  AsyncSpec linear = linear_adaptive_primary(b);
  AsyncSolver adaptive(sys, contact, linear);
  const LoopRecord r = run(adaptive, input, loop);
  EXPECT_EQ(r.primary_nodes.front(), 10);
  EXPECT_EQ(r.primary_nodes.back(), linear_primary_size(linear.primary, std::abs(settled[contact])));
  EXPECT_GT(r.primary_nodes.back(), 10);

  AsyncSpec threshold = linear;
  threshold.primary.kind = PrimarySizePolicy::Kind::kThreshold;
  threshold.primary.threshold = 0.5 * std::abs(settled[contact]);
  AsyncSolver by_threshold(sys, contact, threshold);
  const LoopRecord t = run(by_threshold, input, loop);
  int expected = 0;  // nodes from the tip inward whose displacement exceeds the threshold
  for (int i = contact; i >= 0 && std::abs(settled[i]) > threshold.primary.threshold; --i) ++expected;
  EXPECT_EQ(t.primary_nodes.front(), 10);
  EXPECT_EQ(t.primary_nodes.back(), std::clamp(expected, 10, 30));
}

TEST(AdaptablePrimary, SlidingMaximumMatchesBruteForce) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> dist(0, 40);
  for (int window : {1, 2, 7, 50}) {
    SlidingMax sliding(window);
    std::vector<int> values;
    for (long step = 1; step <= 500; ++step) {
      values.push_back(dist(rng));
      int expected = 0;
      for (std::size_t i = values.size() > static_cast<std::size_t>(window) ? values.size() - window : 0; i < values.size(); ++i)
        expected = std::max(expected, values[i]);
      ASSERT_EQ(sliding.push(step, values.back()), expected) << "window " << window << " step " << step;
    }
  }
}

TEST(AdaptablePrimary, HoldTimeKeepsTheRegionThroughZeroCrossings) {
  // A sine through the probe: the instantaneous size collapses to the minimum near every zero
  // crossing of the deformation; with a hold of one period it stays at the amplitude's size.
  const BarSpec b = soft_bar(40);
  const ReducedSystem sys = damped_bar(b, 0.3);
  const int contact = sys.num_free_nodes() - 1;
  ProbeSignal sine;
  sine.kind = ProbeSignal::Kind::kGrowingSine;
  sine.amplitude = 2e-2;
  sine.start_frequency = 2.0;
  sine.sweep_time = 1e-3;  // full amplitude from the first frame
  AsyncSpec spec = linear_adaptive_primary(b);
  AsyncSolver instantaneous(sys, contact, spec);
  spec.primary.hold_frames = 500;  // one period of the 2 Hz input
  AsyncSolver held(sys, contact, spec);
  const LoopRecord a = run(instantaneous, sine, loop_spec(3000));
  const LoopRecord h = run(held, sine, loop_spec(3000));
  const auto min_late = [](const LoopRecord& r) {
    return *std::min_element(r.primary_nodes.begin() + 1000, r.primary_nodes.end());
  };
  const auto max_late = [](const LoopRecord& r) {
    return *std::max_element(r.primary_nodes.begin() + 1000, r.primary_nodes.end());
  };
  EXPECT_EQ(min_late(a), 10);
  EXPECT_GT(max_late(a), 10);
  EXPECT_EQ(min_late(h), max_late(h));  // steady amplitude, steady size
  EXPECT_EQ(max_late(h), max_late(a));
}

// ---------------------------------------------------------------- configuration

namespace {
std::string config_error(const nlohmann::json& j) {
  try {
    read_run_config(io::JsonReader(j, "run.json"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

nlohmann::json base_config() {
  return nlohmann::json::parse(R"({
    "model": {"kind": "bar", "nodes": 40, "length": 0.04, "area": 1e-4, "youngs_modulus": 5000,
              "density": 1000, "damping": {"ratio": 0.3}},
    "haptics": {"rate": 1000, "duration": 0.2, "probe_stiffness": 10},
    "input": {"kind": "chirp", "amplitude": 0.001, "end_frequency": 5},
    "async": {"primary": {"nodes": 5}, "secondary": [{"every": 20}]}})");
}
}  // namespace

TEST(RunConfig, ErrorsNameThePointer) {
  EXPECT_EQ(config_error(base_config()), "");
  nlohmann::json j = base_config();
  j["async"]["secondary"][0]["nodes"] = 36;  // 34 nodes remain after the primary region
  EXPECT_NE(config_error(j).find("run.json: /async/secondary/0/nodes: expected a region that fits"), std::string::npos);
  j = base_config();
  j["model"]["damping"] = {{"ratio", 0.3}, {"alpha", 2.0}};
  EXPECT_NE(config_error(j).find("/model/damping: expected exactly one of"), std::string::npos);
  j = base_config();
  j["input"]["frequncy"] = 1.0;
  EXPECT_EQ(config_error(j), "run.json: /input/frequncy: unknown field");
}

TEST(RunConfig, SolverObjectsInheritMissingKeysIncludingKind) {
  // async_sim.md: solver.kind defaults to "implicit"; a region's solver object inherits the
  // top-level solver's missing keys, its kind included.
  nlohmann::json j = base_config();
  j["solver"] = {{"implicit_scheme", "newmark"}};
  j["async"]["primary_solver"] = {{"implicit_scheme", "backward_euler"}};
  j["async"]["secondary"][0]["solver"] = {{"kind", "static"}};
  const RunConfig c = read_run_config(io::JsonReader(j, "run.json"));
  EXPECT_EQ(solver_name(c.comparison.whole_solver), "implicit/newmark");
  ASSERT_TRUE(c.comparison.async.has_value());
  EXPECT_EQ(solver_name(c.comparison.async->primary_solver), "implicit/backward_euler");
  EXPECT_EQ(solver_name(c.comparison.async->secondary.at(0).solver), "static");
  j["solver"] = {{"kind", "explicit"}};
  j["async"]["primary_solver"] = {{"explicit_variant", "backward_damping"}};
  EXPECT_EQ(solver_name(read_run_config(io::JsonReader(j, "run.json")).comparison.async->primary_solver),
            "explicit/backward_damping");
}

TEST(RunConfig, SetupErrorsNameTheConfigMemberOfTheSetting) {
  EXPECT_EQ(config_pointer({SettingAtFault::Kind::kWholeSolver}), "/solver");
  EXPECT_EQ(config_pointer({SettingAtFault::Kind::kPrimarySolver}), "/async/primary_solver");
  EXPECT_EQ(config_pointer({SettingAtFault::Kind::kSecondarySolver, 1}), "/async/secondary/1/solver");
  EXPECT_EQ(config_pointer({SettingAtFault::Kind::kProbeStiffness}), "/haptics/probe_stiffness");
  // An explicit secondary region every 20 frames of this bar is far above its limit.
  nlohmann::json j = base_config();
  j["async"]["secondary"][0]["solver"] = {{"kind", "explicit"}};
  const RunConfig config = read_run_config(io::JsonReader(j, "run.json"));
  ModelSummary summary;
  const ReducedSystem sys = build_system(config, summary);
  try {
    run_configured_comparison(sys, config);
    ADD_FAILURE() << "an explicit region above its stability limit ran";
  } catch (const ConfigInputError& e) {
    EXPECT_EQ(e.pointer, "/async/secondary/0/solver");
    EXPECT_EQ(std::string(e.what()).rfind("secondary region 1: explicit step 0.02 s exceeds the stability limit", 0), 0u)
        << e.what();
  }
}

TEST(RunConfig, ExplicitAtTheHapticRateOnAFineBarIsAnInputError) {
  nlohmann::json j = base_config();
  j["solver"] = {{"kind", "explicit"}};
  RunConfig config = read_run_config(io::JsonReader(j, "run.json"));
  ModelSummary summary;
  const ReducedSystem sys = build_system(config, summary);
  EXPECT_LT(summary.explicit_limit_central, 1e-3);
  EXPECT_THROW(run_comparison(sys, config.comparison), InputError);
}

// ---------------------------------------------------------------- resources of a run

namespace {
// The config member a refused config names, or "" when it is accepted.
std::string refused_at(const nlohmann::json& j) {
  try {
    read_run_config(io::JsonReader(j, "run.json"));
  } catch (const ConfigInputError& e) {
    return e.pointer;
  }
  return "";
}

double share_of(const std::vector<MemoryShare>& shares, const std::string& pointer) {
  for (const MemoryShare& s : shares)
    if (s.pointer == pointer) return s.bytes;
  return 0.0;
}

template <typename T>
double held(const std::vector<T>& v) { return static_cast<double>(v.capacity() * sizeof(T)); }
}  // namespace

TEST(RunResources, EstimateCoversTheRecordsARunKeeps) {
  // The per-frame share must bound what the run really holds per frame: the three loops'
  // records and the input frequency.
  nlohmann::json j = base_config();
  j["haptics"]["duration"] = 1.0;
  const RunConfig config = read_run_config(io::JsonReader(j, "run.json"));
  ModelSummary summary;
  const ComparisonResult r = run_comparison(build_system(config, summary), config.comparison);
  double kept = held(r.frequency);
  for (const LoopRecord* rec : {&r.whole, &r.async, &r.exact})
    kept += held(rec->probe) + held(rec->force) + held(rec->contact) + held(rec->primary_nodes);
  const double estimate = share_of(estimate_run_memory(config), "/haptics/duration");
  EXPECT_GE(estimate, kept);
  EXPECT_LE(estimate, 1.5 * kept);  // an estimate, not a blanket refusal
}

TEST(RunResources, TheMemberSettingTheLargestShareIsNamed) {
  nlohmann::json j = base_config();
  EXPECT_EQ(refused_at(j), "");
  // 1e7 frames kept every frame in the artifact: gigabytes of series (estimated on a config read
  // short, so that the test does not depend on this machine's memory limit).
  j["series_every"] = 1;
  RunConfig config = read_run_config(io::JsonReader(j, "run.json"));
  config.comparison.loop.frames = 10000000;
  const std::vector<MemoryShare> shares = estimate_run_memory(config);
  EXPECT_GT(share_of(shares, "/series_every"), 4e9);
  EXPECT_GT(share_of(shares, "/series_every"), share_of(shares, "/haptics/duration"));
  // A dense factorisation per size of an adaptive primary region of a 1e5-node bar: far beyond
  // any machine, refused before anything is built.
  j = base_config();
  j["model"]["nodes"] = 100000;
  j["reference"] = false;
  j["linear_solver"] = "dense";
  j["async"]["primary"] = {{"policy", "linear"}, {"min_nodes", 1}, {"max_nodes", 50000}, {"gradient", 1.0}};
  EXPECT_EQ(refused_at(j), "/linear_solver");
}

TEST(RunResources, AnEndlessRunIsRefusedAtTheDuration) {
  // 1e7 frames of the exact reference on 2000 DOFs: products of a 4000 x 4000 matrix every frame.
  nlohmann::json j = base_config();
  j["model"]["nodes"] = 2001;
  j["haptics"]["duration"] = 1e4;
  j["timing_repeats"] = 1;
  EXPECT_EQ(refused_at(j), "/haptics/duration");
  j["reference"] = false;  // the sparse bar alone: 4e10 element updates, under the limit
  EXPECT_EQ(refused_at(j), "");
}

TEST(RunResources, ProgressCountsEveryFrameOfEveryLoop) {
  nlohmann::json j = base_config();
  j["haptics"]["duration"] = 2 * kProgressFrames / 1000.0;  // two reports a loop
  j["timing_repeats"] = 2;
  RunConfig config = read_run_config(io::JsonReader(j, "run.json"));
  std::vector<long long> seen;
  config.comparison.progress = [&](long long done, double) { seen.push_back(done); };
  ModelSummary summary;
  run_comparison(build_system(config, summary), config.comparison);
  const long long total = total_loop_frames(config.comparison);
  EXPECT_EQ(total, (2 * 2 + 1) * 2 * kProgressFrames);  // 2 repeats of whole and regions, the reference
  ASSERT_EQ(seen.size(), 10u);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_EQ(seen.back(), total);
}
