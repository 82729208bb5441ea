// The far field's fixed-interface modes (Craig–Bampton) on the condensed regions: with no modes
// the Guyan far field is left, bit for bit; the subspace iteration finds the lowest eigenpairs; every mode carries the whole Guyan mass and makes the regions the
// whole linear model under a dynamic input, to round-off; a few lowest modes already remove most
// of the Guyan far field's dynamic error; a region covering the mesh is still the whole model bit
// for bit; the mode count is checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "softsim/dynamics/lumped_mass.hpp"
#include "softsim/haptic/haptic_config.hpp"
#include "softsim/haptic/haptic_run.hpp"
#include "softsim/haptic/haptic_scene.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/regions/primary_region.hpp"
#include "softsim/regions/dof_blocks.hpp"
#include "softsim/regions/far_field_modes.hpp"
#include "softsim/regions/secondary_region.hpp"
#include "softsim/regions/sparse_cholesky.hpp"

#include "support/haptic_block.hpp"
#include "support/scenes.hpp"

using namespace softsim;

namespace {

using Block = test_scenes::HapticBlock;
using test_scenes::press_down;

const Eigen::Vector3d kTop(0.05, 0.05, 0.05);

haptic::HapticOptions modal(double radius, int modes) {
  haptic::HapticOptions opt;
  opt.probe_stiffness = 100;
  opt.use_regions = true;
  opt.regions.radius = radius;
  opt.regions.coupling = regions::Coupling::condensed;
  opt.regions.secondary_every = 10;
  opt.regions.far_field_mass = true;
  opt.regions.far_field_modes = modes;
  return opt;
}

haptic::HapticOptions whole_model() {
  haptic::HapticOptions opt;
  opt.probe_stiffness = 100;
  return opt;
}

// 001 Fig. 6's chirp, 3 mm, 0 → 10 Hz over 0.6 s: fast enough that the far field's own
// dynamics show beyond its static shape.
haptic::ProbePath chirp() {
  haptic::ProbePath path = press_down(kTop, 0.003, 0.1);
  path.kind = haptic::ProbePath::Kind::chirp;
  path.signal.kind = multirate::ProbeSignal::Kind::kChirp;
  path.signal.amplitude = 0.003;
  path.signal.start_frequency = 0;
  path.signal.end_frequency = 10;
  path.signal.sweep_time = 0.6;
  return path;
}

// RMS force difference over the run, relative to the reference's peak force (the experiments'
// measure).
double relative_error(const haptic::HapticRecord& a, const haptic::HapticRecord& ref) {
  double sum = 0, peak = 0;
  for (std::size_t k = 0; k < ref.force.size(); ++k) {
    sum += (a.force[k] - ref.force[k]).squaredNorm();
    peak = std::max(peak, ref.force[k].norm());
  }
  return std::sqrt(sum / static_cast<double>(ref.force.size())) / peak;
}

regions::PrimaryRegion region_at_top(const mesh::TetMesh& m, double radius) {
  int centre = 0;
  for (int i = 0; i < m.num_nodes(); ++i)
    if ((m.nodes[i] - kTop).norm() < 1e-12) centre = i;
  return regions::select_primary_region(m, centre, radius);
}

}  // namespace

// The residual mass Ψᵀ M Ψ − LᵀL left on the interface: Guyan's with no modes, less with each
// mode, none with every mode (the modes then carry the far field's whole inertia).
TEST(ModalFarField, ModesTakeOverTheGuyanMassUntilNoneIsLeft) {
  Block b;
  const auto& m = *b.mesh;
  const regions::PrimaryRegion r = region_at_top(m, 0.03);
  const fem::Material material = b.config(10).material;
  const std::vector<double> masses = dynamics::lumped_mass(m, material.elastic.density);
  const regions::LinearModel linear(m, material, std::vector<char>(3 * m.num_nodes(), 0),
                                    Eigen::VectorXd::Zero(3 * m.num_nodes()), masses);
  auto laid = [&](int modes) {
    regions::CondensedSecondary far(linear, r);
    if (modes > 0) far.use_modes(modes, 1e-4, 10);
    double sum = 0;
    for (double x : far.interface_masses()) sum += x;
    return sum;
  };
  regions::CondensedSecondary probe(linear, r);
  const int all = probe.secondary_dofs();
  const double guyan = laid(0), few = laid(6), every = laid(all);
  ASSERT_GT(guyan, 0.1);
  EXPECT_LT(few, guyan);
  EXPECT_LT(every, 1e-9 * guyan);
  // The modes found are the far field's, ascending and positive (the interface holds it).
  regions::CondensedSecondary far(linear, r);
  far.use_modes(6, 1e-4, 10);
  ASSERT_EQ(far.modes(), 6);
  for (int j = 0; j < 6; ++j) {
    EXPECT_GT(far.mode_omega2()[j], 0.0);
    if (j > 0) EXPECT_GE(far.mode_omega2()[j], far.mode_omega2()[j - 1]);
  }
}

// Zero modes is the Guyan far field itself: the same interface force and the same masses, bit
// for bit.
TEST(ModalFarField, ZeroModesIsGuyan) {
  Block b;
  const auto& m = *b.mesh;
  const regions::PrimaryRegion r = region_at_top(m, 0.03);
  const fem::Material material = b.config(10).material;
  const regions::LinearModel linear(m, material, std::vector<char>(3 * m.num_nodes(), 0),
                                    Eigen::VectorXd::Zero(3 * m.num_nodes()),
                                    dynamics::lumped_mass(m, material.elastic.density));
  regions::CondensedSecondary guyan(linear, r), none(linear, r);
  none.use_modes(0, 1e-4, 10);
  EXPECT_EQ(none.modes(), 0);
  EXPECT_EQ(guyan.interface_masses(), none.interface_masses());
  std::vector<double> u(3 * r.interface.size()), f1(u.size()), f2(u.size());
  for (std::size_t k = 0; k < u.size(); ++k) u[k] = 1e-3 * std::sin(0.7 * static_cast<double>(k));
  guyan.interface_force(u.data(), 0, f1.data());
  none.interface_force(u.data(), 0, f2.data());
  EXPECT_EQ(f1, f2);
}

// Above the dense size the modes come from the subspace iteration: each is an eigenpair of
// (K, M) to a small residual, mass-normalised, and the lowest ones agree with a dense solution.
TEST(ModalFarField, TheSubspaceIterationFindsTheLowestEigenpairs) {
  const mesh::TetMesh m = test_scenes::cuboid(9, 9, 6, 0.1, 0.1, 0.06);
  const fem::Material material = Block().config(10).material;
  std::vector<char> fixed(3 * m.num_nodes(), 0);
  for (int i = 0; i < m.num_nodes(); ++i)
    if (m.nodes[i].z() < 1e-12) fixed[3 * i] = fixed[3 * i + 1] = fixed[3 * i + 2] = 1;
  const regions::LinearModel linear(m, material, fixed, Eigen::VectorXd::Zero(3 * m.num_nodes()));
  const std::vector<int> dofs = regions::free_dofs(m.num_nodes(), fixed, [](int) { return true; });
  ASSERT_GT(dofs.size(), 1500u);  // past the dense path
  const Eigen::SparseMatrix<double> K = regions::dof_block(linear.K, dofs, dofs);
  const std::vector<double> node_mass = dynamics::lumped_mass(m, material.elastic.density);
  Eigen::VectorXd mass(static_cast<int>(dofs.size()));
  for (std::size_t k = 0; k < dofs.size(); ++k) mass[static_cast<int>(k)] = node_mass[dofs[k] / 3];
  regions::SparseCholesky factor;
  factor.factorize(K, "test");
  const regions::FarFieldModes modes = regions::lowest_modes(K, mass, factor, 6);
  ASSERT_EQ(modes.phi.cols(), 6);
  const Eigen::MatrixXd I = modes.phi.transpose() * mass.asDiagonal() * modes.phi;
  EXPECT_LT((I - Eigen::MatrixXd::Identity(6, 6)).norm(), 1e-9);
  for (int j = 0; j < 6; ++j) {
    const Eigen::VectorXd residual = K * modes.phi.col(j) - modes.omega2[j] * mass.asDiagonal() * modes.phi.col(j);
    EXPECT_LT(residual.norm(), 1e-4 * modes.omega2[j] * (mass.asDiagonal() * modes.phi.col(j)).norm()) << j;
  }
  const Eigen::VectorXd s = mass.cwiseSqrt().cwiseInverse();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense(s.asDiagonal() * Eigen::MatrixXd(K) * s.asDiagonal(),
                                                             Eigen::EigenvaluesOnly);
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(modes.omega2[j], dense.eigenvalues()[j], 1e-8 * dense.eigenvalues()[j]) << j;
}

// Every mode kept: the far field in modal coordinates is the far field, and the same central
// difference in those coordinates is the same step; the regions follow the whole linear model
// under the chirp to round-off. With no modes (Guyan) and with a few the error is what the
// truncation leaves, falling with the modes kept.
TEST(ModalFarField, EveryModeIsTheWholeLinearModelAndFewModesBeatGuyan) {
  Block b;
  const haptic::ProbePath path = chirp();
  const long frames = 600;
  haptic::HapticScene whole(b.mesh, b.config(15, "linear"), whole_model());
  const auto rw = haptic::run_haptic(whole, path, frames);
  const regions::LinearModel linear(*b.mesh, b.config(15, "linear").material,
                                    std::vector<char>(3 * b.mesh->num_nodes(), 0), Eigen::VectorXd::Zero(3 * b.mesh->num_nodes()));
  const regions::CondensedSecondary count(linear, region_at_top(*b.mesh, 0.03));  // at least every mode
  double err[3];
  const int modes[3] = {0, 8, count.secondary_dofs()};
  for (int k = 0; k < 3; ++k) {
    haptic::HapticScene regions(b.mesh, b.config(15, "linear"), modal(0.03, modes[k]));
    const auto rr = haptic::run_haptic(regions, path, frames);
    ASSERT_TRUE(regions.events().empty());
    ASSERT_FALSE(regions.regions()->active()->region().interface.empty());
    err[k] = relative_error(rr, rw);
  }
  EXPECT_GT(err[0], 1e-3) << "the chirp should stir the far field's own dynamics";
  EXPECT_LT(err[1], 0.5 * err[0]) << err[1] << " vs Guyan " << err[0];
  EXPECT_LT(err[2], 1e-9) << err[2];
}

TEST(ModalFarField, APrimaryRegionCoveringTheMeshIsStillTheWholeModelBitForBit) {
  Block b;
  const haptic::ProbePath path = press_down(kTop, 0.008, 0.2);
  haptic::HapticScene whole(b.mesh, b.config(15), whole_model());
  haptic::HapticScene all(b.mesh, b.config(15), modal(1.0, 12));  // no far field: no modes
  const auto rw = haptic::run_haptic(whole, path, 300);
  const auto ra = haptic::run_haptic(all, path, 300);
  for (std::size_t k = 0; k < rw.force.size(); ++k)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(rw.force[k][c], ra.force[k][c]) << "frame " << k;
}

TEST(ModalFarField, TheModeCountIsChecked) {
  Block b;
  auto bad = modal(0.03, 4);
  bad.regions.far_field_mass = false;  // modes without the Guyan far field they complete
  haptic::HapticScene without_mass(b.mesh, b.config(15, "linear"), bad);
  EXPECT_THROW(haptic::run_haptic(without_mass, press_down(kTop, 0.003, 0.1), 20), InputError);
  haptic::HapticScene negative(b.mesh, b.config(15, "linear"), modal(0.03, -1));
  EXPECT_THROW(haptic::run_haptic(negative, press_down(kTop, 0.003, 0.1), 20), InputError);
  const nlohmann::json model = {{"mesh", "unused"},
                                {"material", {{"E", 5000.0}, {"nu", 0.35}, {"density", 1000.0}}},
                                {"boundary", {{"fixed", {{{"set", "bottom"}}}}}}};
  const nlohmann::json input = {{"kind", "press"}, {"start", {0.05, 0.05, 0.06}}, {"direction", {0, 0, -1}},
                                {"depth", 0.005}, {"ramp_time", 0.2}};
  auto read = [&](const nlohmann::json& regions) {
    const nlohmann::json cfg = {{"model", model}, {"probe", {{"stiffness", 100}}}, {"input", input}, {"regions", regions}};
    return haptic::read_haptic_config(io::JsonReader(cfg, "scene.json"), *b.mesh);
  };
  EXPECT_EQ(read({{"radius", 0.02}, {"secondary", "guyan"}, {"modes", 7}}).options.regions.far_field_modes, 7);
  for (const nlohmann::json& regions : {nlohmann::json{{"radius", 0.02}, {"modes", 4}},
                                        nlohmann::json{{"radius", 0.02}, {"secondary", "guyan"}, {"modes", -1}},
                                        nlohmann::json{{"radius", 0.02}, {"secondary", "guyan"}, {"modes", 1.5}}}) {
    try {
      read(regions);
      ADD_FAILURE() << regions.dump();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("/regions/modes"), std::string::npos) << e.what();
    }
  }
}
