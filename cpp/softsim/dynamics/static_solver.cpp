// GCC 12 reports false "may be used uninitialized" warnings inside the AVX-512 intrinsics
// used by Eigen's dense GEMM packing, which SparseLU instantiates; the intrinsic headers are
// first included through the line below, so the suppression has to precede it.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include "softsim/dynamics/static_solver.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#ifdef SOFTSIM_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/fem/assembly.hpp"
#include "softsim/io/errors.hpp"

namespace softsim::dynamics {

namespace {

double inf_norm_free(const Eigen::VectorXd& r, const std::vector<char>& mask) {
  double m = 0;
  for (Eigen::Index q = 0; q < r.size(); ++q)
    if (!mask[q]) m = std::max(m, std::abs(r[q]));
  return m;
}

// K is symmetric positive definite away from instabilities: CHOLMOD's supernodal Cholesky when the
// build has it (the ANP and smoothed tangents couple each node's whole patch, and the simplicial
// factor of that wider stencil took 95 % of a 10 240-tet static solve), else Eigen's simplicial
// LDLᵀ; LU when the factorisation fails (an indefinite tangent).
class LinearSolver {
 public:
  explicit LinearSolver(const Eigen::SparseMatrix<double>& pattern) {
#ifdef SOFTSIM_HAVE_CHOLMOD
    llt_.analyzePattern(pattern);
#else
    ldlt_.analyzePattern(pattern);
#endif
  }
  bool solve(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
#ifdef SOFTSIM_HAVE_CHOLMOD
    llt_.factorize(K);
    if (llt_.info() == Eigen::Success) {
      x = llt_.solve(b);
      if (llt_.info() == Eigen::Success && x.allFinite()) return true;
    }
    ldlt_.compute(K);
#else
    ldlt_.factorize(K);
#endif
    if (ldlt_.info() == Eigen::Success) {
      x = ldlt_.solve(b);
      if (ldlt_.info() == Eigen::Success && x.allFinite()) return true;
    }
    lu_.compute(K);
    if (lu_.info() != Eigen::Success) return false;
    x = lu_.solve(b);
    return lu_.info() == Eigen::Success && x.allFinite();
  }

 private:
#ifdef SOFTSIM_HAVE_CHOLMOD
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> llt_;
#endif
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_;
};

}  // namespace

StaticResult solve_static(const mesh::TetMesh& mesh, const std::vector<fem::ElementKind>& kinds,
                          const fem::Material& material, const Scene& scene, const StaticOptions& opt) {
  if (opt.increments < 1) throw InputError("solver: increments must be at least 1");
  if (opt.max_iterations < 1) throw InputError("solver: max_iterations must be at least 1");
  if (!(opt.tolerance > 0)) throw InputError("solver: tolerance must be positive");
  const int n = mesh.num_nodes();
  const int n3 = 3 * n;
  const fem::Assembler assembler(mesh, kinds, material);
  const std::vector<double> mass = lumped_mass(mesh, material.elastic.density);
  const std::vector<ConstrainedDof> dofs = resolve_constraints(scene, n);
  const std::vector<char> mask = constrained_mask(dofs, n);
  if (scene.has_probe && (scene.probe.node < 0 || scene.probe.node >= n)) throw InputError("probe: node out of range");

  // Loads at full scale (constant part of R).
  Eigen::VectorXd R_full = Eigen::VectorXd::Zero(n3);
  for (int i = 0; i < n; ++i) R_full.segment<3>(3 * i) += mass[i] * scene.gravity;
  for (const auto& load : scene.loads)
    for (int node : load.nodes) {
      if (node < 0 || node >= n) throw InputError("load \"" + load.name + "\": node out of range");
      R_full.segment<3>(3 * node) += load.force_per_node;
    }
  // A force scale for the convergence test that does not vanish with the load.
  double volume = 0;
  for (int e = 0; e < mesh.num_tets(); ++e) volume += mesh::signed_volume(mesh, mesh.tets[e]);
  const double h = std::cbrt(volume / mesh.num_tets());
  const double force_floor = 1e-6 * material.elastic.youngs_modulus * h * h;

  StaticResult res;
  // Every element linear (000 eqs. 4–12): F_int = K u with a constant K, the loads, constraints and
  // probe spring are linear too, so one solve of K u = R is the exact solution. No load
  // increments are needed, and no inversion check: the small-strain model does not see the
  // deformed geometry, so a solution whose mapped geometry inverts is still its solution.
  res.linear_solve = std::all_of(kinds.begin(), kinds.end(), [](fem::ElementKind k) { return k == fem::ElementKind::linear; });
  const int increments = res.linear_solve ? 1 : opt.increments;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n3);
  Eigen::VectorXd f_int(n3), r(n3), R(n3), du(n3), rhs(n3), target(n3);
  Eigen::SparseMatrix<double> K = assembler.pattern();
  LinearSolver solver(K);

  auto external = [&](double lambda, const Eigen::VectorXd& uu, Eigen::VectorXd& out) {
    out = lambda * R_full;
    if (scene.has_probe) {
      const int p = scene.probe.node;
      out.segment<3>(3 * p) += scene.probe.stiffness * (lambda * scene.probe.displacement - uu.segment<3>(3 * p));
    }
  };
  auto residual = [&](double lambda, const Eigen::VectorXd& uu, Eigen::VectorXd& out, double& scale) {
    assembler.internal_forces(uu.data(), f_int);
    external(lambda, uu, R);
    out = f_int - R;
    scale = std::max({f_int.lpNorm<Eigen::Infinity>(), R.lpNorm<Eigen::Infinity>(), force_floor});
  };

  // Total potential Π = W(u) − λ R·u + ½ k |λ d − u_probe|², whose gradient is the residual. Near
  // incompressibility a full Newton step can raise the residual norm while lowering Π (the
  // quadratic part of J times a large bulk modulus), so a step is also accepted when Π falls.
  auto potential = [&](double lambda, const Eigen::VectorXd& uu) {
    double pi = assembler.strain_energy(uu.data()) - lambda * R_full.dot(uu);
    if (scene.has_probe) {
      const int p = scene.probe.node;
      pi += 0.5 * scene.probe.stiffness * (lambda * scene.probe.displacement - uu.segment<3>(3 * p)).squaredNorm();
    }
    return pi;
  };

  for (int inc = 1; inc <= increments; ++inc) {
    const double lambda = static_cast<double>(inc) / increments;
    target = u;
    for (const auto& d : dofs) target[3 * d.node + d.component] = lambda * d.value;
    int it = 0;
    double scale = 0, rnorm = 0;
    residual(lambda, u, r, scale);
    for (;; ++it) {
      double jump = 0;  // constraint increment still to impose
      for (const auto& d : dofs)
        jump = std::max(jump, std::abs(target[3 * d.node + d.component] - u[3 * d.node + d.component]));
      rnorm = inf_norm_free(r, mask);
      if (rnorm <= opt.tolerance * scale && jump == 0.0) break;
      if (it >= opt.max_iterations) {
        std::ostringstream msg;
        msg << "static: increment " << inc << "/" << increments << " did not converge in " << opt.max_iterations
            << " Newton iterations: residual " << rnorm << " N > limit " << opt.tolerance * scale << " N";
        throw NumericalError(msg.str());
      }
      // Newton step with the constraint increment imposed: K_ff du_f = −r_f − K_fc Δu_c.
      assembler.tangent(u.data(), K);
      Eigen::VectorXd duc = Eigen::VectorXd::Zero(n3);
      for (const auto& d : dofs) duc[3 * d.node + d.component] = target[3 * d.node + d.component] - u[3 * d.node + d.component];
      rhs = -r - K * duc;
      if (scene.has_probe) {
        const int p = scene.probe.node;
        for (int k = 0; k < 3; ++k) rhs[3 * p + k] -= scene.probe.stiffness * duc[3 * p + k];
      }
      for (int outer = 0; outer < K.outerSize(); ++outer)
        for (Eigen::SparseMatrix<double>::InnerIterator itK(K, outer); itK; ++itK) {
          const auto row = itK.row(), col = itK.col();
          if (mask[row] || mask[col]) itK.valueRef() = row == col ? 1.0 : 0.0;
          else if (scene.has_probe && row == col && row / 3 == scene.probe.node) itK.valueRef() += scene.probe.stiffness;
        }
      for (Eigen::Index q = 0; q < n3; ++q)
        if (mask[q]) rhs[q] = duc[q];
      if (!solver.solve(K, rhs, du)) {
        std::ostringstream msg;
        msg << "static: increment " << inc << ", iteration " << it
            << ": the tangent stiffness is singular (are rigid motions left unconstrained?)";
        throw NumericalError(msg.str());
      }
      // Backtracking: no inverted element, and no growth of the residual unless the step also
      // imposes a constraint increment (which legitimately raises it).
      auto free_norm2 = [&](const Eigen::VectorXd& v) {
        double s2 = 0;
        for (Eigen::Index q = 0; q < n3; ++q)
          if (!mask[q]) s2 += v[q] * v[q];
        return s2;
      };
      const double old_norm = free_norm2(r);
      const double old_energy = jump > 0 ? 0.0 : potential(lambda, u);
      double step = 1.0, trial_scale = 0;
      Eigen::VectorXd trial(n3), r_trial(n3);
      bool accepted = false;
      for (int ls = 0; ls < 20; ++ls, step *= 0.5) {
        trial = u + step * du;
        if (step == 1.0)
          for (const auto& d : dofs) trial[3 * d.node + d.component] = target[3 * d.node + d.component];
        if (!res.linear_solve && assembler.min_volume_ratio(trial.data()) <= 0) continue;
        residual(lambda, trial, r_trial, trial_scale);
        if (jump > 0 || free_norm2(r_trial) <= old_norm || ls >= 8 || potential(lambda, trial) < old_energy) {
          accepted = true;
          break;
        }
      }
      if (!accepted) {
        int e = -1;
        const Eigen::VectorXd full = u + du;
        const double J = assembler.min_volume_ratio(full.data(), &e);
        std::ostringstream msg;
        msg << "static: increment " << inc << ", iteration " << it << ": every step length inverts element " << e
            << " (J = " << J << " <= 0); use more increments";
        throw NumericalError(msg.str());
      }
      u = trial;
      r = r_trial;
      scale = trial_scale;
    }
    res.iterations.push_back(it);
    res.residual = rnorm;
    res.force_scale = scale;
  }

  res.displacement.assign(u.data(), u.data() + n3);
  res.reactions.assign(scene.constraints.size(), Eigen::Vector3d::Zero());
  for (const auto& d : dofs) res.reactions[d.constraint][d.component] += r[3 * d.node + d.component];
  res.strain_energy = assembler.strain_energy(u.data());
  if (scene.has_probe) {
    const int p = scene.probe.node;
    res.probe_force = scene.probe.stiffness * (scene.probe.displacement - u.segment<3>(3 * p));
  }
  return res;
}

}  // namespace softsim::dynamics
