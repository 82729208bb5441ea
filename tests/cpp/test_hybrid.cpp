// Dual-mode partitioning (000 §2.2.1) and the dhd_sim configuration: the linear share is met
// exactly with the farthest elements linear first, layers / tags / sphere / strain-driven
// splits select what they claim, corotational can replace linear, interface nodes need no
// special treatment (summed forces, exact where the kinds agree), the config is read strictly, and
// the executable's exit codes follow the contract (2 for a refused time step, 3 and no
// artifact for a numerical failure).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>

#include <Eigen/Geometry>

#include "softsim/dynamics/node_selection.hpp"
#include "softsim/dynamics/static_solver.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/hybrid/dhd_run.hpp"
#include "softsim/hybrid/dhd_scene.hpp"
#include "softsim/hybrid/partition.hpp"
#include "softsim/io/artifact.hpp"
#include "softsim/io/atomic_file.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/mesh/cuboid.hpp"
#include "softsim/mesh/vtu_reader.hpp"

#include "support/fields.hpp"
#include "support/scenes.hpp"

using namespace softsim;
using fem::ElementKind;
namespace fs = std::filesystem;

namespace {

using test_scenes::affine_boundary_scene;
using test_scenes::constraint;
using test_scenes::cuboid;
using test_scenes::kPaper;

int count(const std::vector<ElementKind>& k, ElementKind kind) {
  return static_cast<int>(std::count(k.begin(), k.end(), kind));
}

hybrid::DhdConfig parse(const nlohmann::json& j, const mesh::TetMesh& m) {
  const io::JsonReader r(j, "test.json");
  return hybrid::read_dhd_config(r, m);
}

// A scratch directory under the build tree, removed at the end of the test.
struct Scratch {
  fs::path dir;
  explicit Scratch(const std::string& name) : dir(fs::path(SOFTSIM_BIN_DIR) / ".." / ("test_hybrid_" + name)) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Scratch() { fs::remove_all(dir); }
  std::string path(const std::string& f) const { return (dir / f).string(); }
};

void write_json(const std::string& path, const nlohmann::json& j) { std::ofstream(path) << j.dump(1); }

int run_dhd_sim(const std::string& config, const std::string& out, const std::string& extra = "") {
  const std::string cmd = std::string(SOFTSIM_BIN_DIR) + "/dhd_sim " + extra + " --config " + config + " --out " + out +
                          " > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WEXITSTATUS(status);
}

}  // namespace

TEST(Partition, LinearFractionIsExactAndFarthestFirst) {
  const auto m = cuboid(6, 6, 4, 0.06, 0.06, 0.04);  // 720 elements
  const auto centroids = hybrid::element_centroids(m);
  const Eigen::Vector3d p = hybrid::default_operating_point(m);
  EXPECT_TRUE(p.isApprox(Eigen::Vector3d(0.03, 0.03, 0.04)));
  for (double r : {0.0, 0.1, 0.25, 0.333, 0.5, 1.0}) {
    hybrid::PartitionSpec s;
    s.kind = hybrid::PartitionKind::linear_fraction;
    s.linear_fraction = r;
    const auto kinds = hybrid::make_partition(m, s);
    EXPECT_EQ(count(kinds, ElementKind::linear), std::llround(r * m.num_tets())) << "r = " << r;
    double nearest_linear = 1e300, farthest_tled = 0;
    for (int e = 0; e < m.num_tets(); ++e) {
      const double d = (centroids[e] - p).norm();
      if (kinds[e] == ElementKind::linear) nearest_linear = std::min(nearest_linear, d);
      else farthest_tled = std::max(farthest_tled, d);
    }
    if (r > 0 && r < 1) EXPECT_GE(nearest_linear, farthest_tled);
  }
}

TEST(Partition, DepthDistanceMakesTheLowestElementsLinear) {
  const auto m = cuboid(4, 4, 5, 0.04, 0.04, 0.05);
  hybrid::PartitionSpec s;
  s.kind = hybrid::PartitionKind::linear_fraction;
  s.linear_fraction = 0.4;  // exactly the two bottom layers
  s.distance = hybrid::DistanceMetric::depth;
  const auto kinds = hybrid::make_partition(m, s);
  const auto& layer = m.element_tags.at("layer");
  for (int e = 0; e < m.num_tets(); ++e)
    EXPECT_EQ(kinds[e], layer[e] < 2 ? ElementKind::linear : ElementKind::tled) << "element " << e;
}

TEST(Partition, TopLayersNonlinear) {
  const auto m = cuboid(3, 3, 5, 0.03, 0.03, 0.05);
  hybrid::PartitionSpec s;
  s.kind = hybrid::PartitionKind::layers;
  s.nonlinear_layers = 2;
  const auto kinds = hybrid::make_partition(m, s);
  const auto& layer = m.element_tags.at("layer");
  for (int e = 0; e < m.num_tets(); ++e) EXPECT_EQ(kinds[e] == ElementKind::tled, layer[e] >= 3);
  s.linear_element = ElementKind::corotational;
  const auto corot = hybrid::make_partition(m, s);
  EXPECT_EQ(count(corot, ElementKind::linear), 0);
  EXPECT_EQ(count(corot, ElementKind::corotational), 3 * 45);
}

TEST(Partition, TagsSphereAndMissingTag) {
  auto m = cuboid(4, 4, 4, 0.04, 0.04, 0.04);
  auto& region = m.element_tags["region"];
  for (int e = 0; e < m.num_tets(); ++e) region[e] = e % 3;
  hybrid::PartitionSpec t;
  t.kind = hybrid::PartitionKind::tags;
  t.tag = "region";
  t.nonlinear_values = {2};
  const auto kt = hybrid::make_partition(m, t);
  for (int e = 0; e < m.num_tets(); ++e) EXPECT_EQ(kt[e] == ElementKind::tled, e % 3 == 2);
  hybrid::PartitionSpec s;
  s.kind = hybrid::PartitionKind::sphere;
  s.center = Eigen::Vector3d(0.02, 0.02, 0.04);
  s.radius = 0.015;
  const auto ks = hybrid::make_partition(m, s);
  const auto c = hybrid::element_centroids(m);
  int inside = 0;
  for (int e = 0; e < m.num_tets(); ++e) {
    EXPECT_EQ(ks[e] == ElementKind::tled, (c[e] - s.center).norm() <= s.radius);
    inside += ks[e] == ElementKind::tled;
  }
  EXPECT_GT(inside, 0);
  EXPECT_LT(inside, m.num_tets());
  t.tag = "no_such_tag";
  EXPECT_THROW(hybrid::make_partition(m, t), InputError);
}

TEST(Partition, StrainDrivenSplitFollowsTheReferenceSolution) {
  // Reference: static TLED solution of a pushed top centre. The strained region is under the
  // tool: by threshold and by fraction, the most strained elements become TLED.
  const auto m = cuboid(5, 5, 3, 0.05, 0.05, 0.03);
  dynamics::Scene scene;
  dynamics::DisplacementConstraint push;
  push.nodes = {dynamics::nearest_node(m, Eigen::Vector3d(0.025, 0.025, 0.03))};
  push.displacement = Eigen::Vector3d(0, 0, -0.005);
  scene.constraints = {constraint(m, "bottom", Eigen::Vector3d::Zero()), push};
  const auto ref = dynamics::solve_static(m, std::vector<ElementKind>(m.num_tets(), ElementKind::tled),
                                          fem::Material::make(kPaper, material::NeoHookeanForm::paper), scene, {});
  const auto strain = hybrid::element_strain(m, ref.displacement, hybrid::StrainMeasure::green_lagrange);
  hybrid::PartitionSpec s;
  s.kind = hybrid::PartitionKind::strain;
  s.reference_displacement = ref.displacement;
  s.measure = hybrid::StrainMeasure::green_lagrange;
  s.threshold = 0.02;
  const auto by_threshold = hybrid::make_partition(m, s);
  for (int e = 0; e < m.num_tets(); ++e) EXPECT_EQ(by_threshold[e] == ElementKind::tled, strain[e] > 0.02);
  EXPECT_GT(count(by_threshold, ElementKind::tled), 0);
  s.threshold.reset();
  s.linear_fraction = 0.8;
  const auto by_fraction = hybrid::make_partition(m, s);
  EXPECT_EQ(count(by_fraction, ElementKind::linear), std::llround(0.8 * m.num_tets()));
  double max_linear = 0, min_tled = 1e300;
  for (int e = 0; e < m.num_tets(); ++e)
    (by_fraction[e] == ElementKind::linear ? max_linear : min_tled) =
        by_fraction[e] == ElementKind::linear ? std::max(max_linear, strain[e]) : std::min(min_tled, strain[e]);
  EXPECT_LE(max_linear, min_tled);
  // The strain under the tool is the largest.
  const int top_centre_element = static_cast<int>(std::max_element(strain.begin(), strain.end()) - strain.begin());
  EXPECT_LT((hybrid::element_centroids(m)[top_centre_element] - Eigen::Vector3d(0.025, 0.025, 0.03)).norm(), 0.015);
}

namespace {
// Static solve with every boundary node prescribed to X ↦ F X; returns the largest deviation
// of an interior node from the same affine map.
double mixed_patch_error(const mesh::TetMesh& m, const std::vector<ElementKind>& kinds, const Eigen::Matrix3d& F) {
  dynamics::StaticOptions opt;
  opt.increments = 2;
  opt.tolerance = 1e-11;
  const auto r = dynamics::solve_static(m, kinds, fem::Material::make(kPaper, material::NeoHookeanForm::paper),
                                        affine_boundary_scene(m, F), opt);
  const auto& b = m.node_sets.at("boundary");
  double err = 0;
  for (int i = 0; i < m.num_nodes(); ++i) {
    if (std::binary_search(b.begin(), b.end(), i)) continue;
    const Eigen::Vector3d expected = (F - Eigen::Matrix3d::Identity()) * m.nodes[i];
    for (int k = 0; k < 3; ++k) err = std::max(err, std::abs(r.displacement[3 * i + k] - expected[k]));
  }
  return err;
}
}  // namespace

TEST(Hybrid, InterfaceNodesNeedNoTreatment) {
  // Element forces are simply summed at every node (000 §2.2.3). Where the kinds share a
  // constitutive response the mixed mesh is as exact as a uniform one: linear and corotational
  // elements coincide for a rotation-free (symmetric) F of any size, so a checkerboard of the two
  // passes the patch test exactly.
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  std::vector<ElementKind> lin_corot(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) lin_corot[e] = e % 2 ? ElementKind::linear : ElementKind::corotational;
  Eigen::Matrix3d U;
  U << 1.08, 0.03, -0.02, 0.03, 0.94, 0.04, -0.02, 0.04, 1.05;
  EXPECT_LT(mixed_patch_error(m, lin_corot, U), 1e-10 * 0.03);
  // With all three kinds the laws differ at second order in the strain, and so does the
  // deviation from the homogeneous field: no first-order error from the interfaces.
  std::vector<ElementKind> three(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) three[e] = static_cast<ElementKind>(e % 3);
  Eigen::Matrix3d H;
  H << 0.5, 0.2, 0.0, -0.1, -0.3, 0.3, 0.0, 0.2, 0.2;
  std::vector<double> relative;
  for (double eps : {1e-2, 1e-3}) {
    const double err = mixed_patch_error(m, three, Eigen::Matrix3d::Identity() + eps * H);
    relative.push_back(err / (eps * 0.03));
  }
  EXPECT_LT(relative[0], 0.05);
  EXPECT_NEAR(relative[1] / relative[0], 0.1, 0.03);
}

TEST(Config, FullConfigIsReadAndSelectorsResolved) {
  const auto m = cuboid(4, 4, 2, 0.04, 0.04, 0.02);
  const nlohmann::json j = nlohmann::json::parse(R"({
    "mesh": "unused.json",
    "material": {"model": "neo_hookean_decoupled", "E": 3000, "nu": 0.45, "density": 1100},
    "damping": {"alpha": 3.0},
    "partition": {"linear_fraction": 0.25, "linear_element": "corotational", "distance": "depth"},
    "boundary": {
      "fixed": ["bottom", {"set": "x_min", "components": "x"}],
      "prescribed": [{"nearest": [0.02, 0.02, 0.02], "displacement": [0, 0, -0.002], "ramp_time": 0.1,
                      "ramp": "smooth", "components": "z"}],
      "forces": [{"box": {"min": [0.04, 0, 0], "max": [0.04, 0.04, 0.02]}, "force": [0.3, 0, 0], "per": "total"}],
      "gravity": [0, 0, -9.81],
      "probe": {"nodes": [7], "stiffness": 20, "displacement": [0, 0.001, 0]}
    },
    "solver": {"kind": "explicit", "steps": 50, "safety_factor": 0.5},
    "output": {"trajectories": [3, {"sphere": {"center": [0, 0, 0], "radius": 1e-6}}], "trajectory_interval": 5},
    "threads": 2
  })");
  const auto c = parse(j, m);
  EXPECT_EQ(std::get<material::NeoHookean>(c.material.law).form, material::NeoHookeanForm::decoupled);
  EXPECT_DOUBLE_EQ(c.material.elastic.poisson_ratio, 0.45);
  EXPECT_DOUBLE_EQ(c.damping_alpha, 3.0);
  EXPECT_EQ(c.partition.kind, hybrid::PartitionKind::linear_fraction);
  EXPECT_EQ(c.partition.linear_element, ElementKind::corotational);
  ASSERT_EQ(c.scene.constraints.size(), 3u);
  EXPECT_EQ(c.scene.constraints[0].nodes, m.node_sets.at("bottom"));
  EXPECT_EQ(c.scene.constraints[1].components, (std::array<bool, 3>{true, false, false}));
  EXPECT_EQ(c.scene.constraints[2].nodes, std::vector<int>{dynamics::nearest_node(m, Eigen::Vector3d(0.02, 0.02, 0.02))});
  EXPECT_EQ(c.scene.constraints[2].ramp.shape, dynamics::Ramp::Shape::smooth);
  ASSERT_EQ(c.scene.loads.size(), 1u);
  EXPECT_EQ(c.scene.loads[0].nodes, m.node_sets.at("x_max"));
  EXPECT_NEAR(c.scene.loads[0].force_per_node.x() * c.scene.loads[0].nodes.size(), 0.3, 1e-12);
  EXPECT_TRUE(c.scene.has_probe);
  EXPECT_EQ(c.scene.probe.node, 7);
  EXPECT_EQ(c.output.trajectory_nodes, (std::vector<int>{3, 0}));
  EXPECT_EQ(c.threads, 2);
  EXPECT_EQ(c.explicit_solver.steps, 50);
}

TEST(Config, StrictReadingNamesThePointer) {
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  auto expect_error = [&](const nlohmann::json& j, const std::string& pointer) {
    try {
      parse(j, m);
      ADD_FAILURE() << "accepted " << j.dump();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(pointer), std::string::npos) << e.what();
    }
  };
  expect_error({{"mesh", "m"}, {"solver", {{"stepz", 10}}}}, "/solver/stepz");
  expect_error({{"mesh", "m"}, {"boundary", {{"fixed", {"no_such_set"}}}}}, "/boundary/fixed/0");
  expect_error({{"mesh", "m"}, {"boundary", {{"prescribed", {{{"set", "top"}, {"nodes", {1}}, {"displacement", {0, 0, 0}}}}}}}},
               "/boundary/prescribed/0");
  expect_error({{"mesh", "m"}, {"boundary", {{"fixed", {{{"sphere", {{"center", {5, 5, 5}}, {"radius", 0.1}}}}}}}}},
               "/boundary/fixed/0");
  expect_error({{"mesh", "m"}, {"material", {{"nu", 0.5}}}}, "/material/nu");
  expect_error({{"mesh", "m"}, {"material", {{"model", "linear"}}}, {"partition", {{"linear_fraction", 0.5}}}}, "/partition");
  expect_error({{"mesh", "m"}, {"solver", {{"kind", "static"}, {"steps", 10}}}}, "/solver/steps");
  expect_error({{"mesh", "m"}, {"partition", {{"linear_fraction", 1.5}}}}, "/partition/linear_fraction");
  expect_error({{"mesh", "m"}, {"output", {{"vtu", "a.vtu"}, {"vtu_format", "binary"}}}}, "/output/vtu_format");
  expect_error({{"mesh", "m"}, {"output", {{"vtu_format", "ascii"}}}}, "/output");
  expect_error({{"mesh", "m"}, {"boundary", {{"gravity", {{"acceleration", {0, 0, -9.81}}, {"ramp_tim", 1}}}}}},
               "/boundary/gravity/ramp_tim");
  expect_error({{"mesh", "m"}, {"boundary", {{"gravity", {{"acceleration", {0, 0, -9.81}}, {"ramp_time", -1}}}}}},
               "/boundary/gravity/ramp_time");
  expect_error({{"mesh", "m"}, {"boundary", {{"gravity", {{"ramp_time", 1}}}}}}, "/boundary/gravity");
}

// Gravity is a vector (constant) or an object with the ramp options of a force.
TEST(Config, GravityTakesTheRampOfAForce) {
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  const auto constant = parse({{"mesh", "m"}, {"boundary", {{"gravity", {0, 0, -9.81}}}}}, m);
  EXPECT_EQ(constant.scene.gravity, Eigen::Vector3d(0, 0, -9.81));
  EXPECT_EQ(constant.scene.gravity_ramp.duration, 0.0);
  const auto ramped = parse({{"mesh", "m"},
                             {"boundary",
                              {{"gravity", {{"acceleration", {0, 1, -9.81}}, {"ramp_time", 0.2}, {"ramp", "smooth"}}}}}},
                            m);
  EXPECT_EQ(ramped.scene.gravity, Eigen::Vector3d(0, 1, -9.81));
  EXPECT_EQ(ramped.scene.gravity_ramp.duration, 0.2);
  EXPECT_EQ(ramped.scene.gravity_ramp.shape, dynamics::Ramp::Shape::smooth);
}

// fem::kElementKinds is the one table of element kinds: every kind has a distinct name that
// parses back to it and a description, and both kinds of partition slot (small-strain and
// nonlinear) have a member.
TEST(ElementKinds, EveryKindHasANameThatParsesBackAndADescription) {
  std::set<std::string> names;
  int small_strain = 0;
  for (int k = 0; k < fem::kNumElementKinds; ++k) {
    const auto kind = static_cast<ElementKind>(k);
    const fem::ElementKindInfo& info = fem::kind_info(kind);
    EXPECT_EQ(static_cast<int>(info.kind), k);
    const std::string name = fem::kind_name(kind);
    EXPECT_FALSE(name.empty());
    EXPECT_NE(name, "unknown");
    EXPECT_GT(std::string(info.description).size(), 10u) << name;
    ASSERT_TRUE(fem::parse_kind(name).has_value()) << name;
    EXPECT_EQ(*fem::parse_kind(name), kind);
    names.insert(name);
    small_strain += info.small_strain;
    EXPECT_NE(fem::kind_legend_text().find(std::to_string(k) + " " + name), std::string::npos) << name;
  }
  EXPECT_EQ(names.size(), static_cast<std::size_t>(fem::kNumElementKinds));
  EXPECT_EQ(fem::kind_names().size(), names.size());
  EXPECT_EQ(fem::kind_names(true).size(), static_cast<std::size_t>(small_strain));
  EXPECT_EQ(fem::kind_names(false).size(), names.size() - small_strain);
  EXPECT_GT(small_strain, 0);
  EXPECT_LT(small_strain, fem::kNumElementKinds);
  EXPECT_FALSE(fem::parse_kind("unknown").has_value());
}

// A run with every kind present: the artifact's legend lists every kind in code order, and the
// counts give each kind (ANP included) and the small-strain share.
TEST(ElementKinds, ArtifactLegendAndCountsListEveryKind) {
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);  // 90 elements
  const nlohmann::json j = {
      {"mesh", "m"},
      {"boundary", {{"fixed", {"bottom"}}, {"prescribed", {{{"set", "top"}, {"displacement", {0, 0, -0.001}}}}}}},
      {"solver", {{"steps", 5}}}};
  const hybrid::DhdConfig c = parse(j, m);
  std::vector<ElementKind> kinds(m.num_tets());
  std::vector<int> expected(fem::kNumElementKinds, 0);
  for (int e = 0; e < m.num_tets(); ++e) {
    const int k = (e * 7) % fem::kNumElementKinds;
    kinds[e] = static_cast<ElementKind>(k);
    ++expected[k];
  }
  const hybrid::DhdRun run = hybrid::run_dhd(m, c, kinds, {});
  const nlohmann::json p = hybrid::result_payload(m, c, run);
  const nlohmann::json& legend = p.at("element_kind_legend");
  ASSERT_EQ(legend.size(), static_cast<std::size_t>(fem::kNumElementKinds));
  int small_strain = 0;
  for (int k = 0; k < fem::kNumElementKinds; ++k) {
    const fem::ElementKindInfo& info = fem::kElementKinds[k];
    EXPECT_EQ(legend[k].at("name"), info.name);
    EXPECT_EQ(legend[k].at("small_strain"), info.small_strain);
    EXPECT_EQ(legend[k].at("description"), info.description);
    EXPECT_GT(expected[k], 0);
    EXPECT_EQ(p.at("element_counts").at(info.name), expected[k]) << info.name;
    if (info.small_strain) small_strain += expected[k];
  }
  EXPECT_EQ(p.at("element_counts").size(), static_cast<std::size_t>(fem::kNumElementKinds) + 1);
  EXPECT_DOUBLE_EQ(p.at("element_counts").at("linear_fraction").get<double>(),
                   static_cast<double>(small_strain) / m.num_tets());
  for (std::size_t e = 0; e < kinds.size(); ++e) EXPECT_EQ(p.at("element_kind")[e], static_cast<int>(kinds[e]));
  // The bench and the run's timing name the kinds by the same table.
  for (const auto& [name, ns] : p.at("timing").at("ns_per_element").items()) EXPECT_TRUE(fem::parse_kind(name)) << name;
}

TEST(Run, HybridWithZeroLinearShareIsExactlyTled) {
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  nlohmann::json j = {{"mesh", "m"},
                      {"boundary", {{"fixed", {"bottom"}}, {"prescribed", {{{"set", "top"}, {"displacement", {0, 0, -0.003}}}}}}},
                      {"solver", {{"steps", 100}}}};
  const auto tled = hybrid::run_dhd(m, parse(j, m));
  j["partition"] = {{"linear_fraction", 0.0}};
  const auto hyb = hybrid::run_dhd(m, parse(j, m));
  EXPECT_EQ(tled.explicit_result->displacement, hyb.explicit_result->displacement);
  j["partition"] = {{"linear_fraction", 0.5}};
  const auto half = hybrid::run_dhd(m, parse(j, m));
  EXPECT_NE(tled.explicit_result->displacement, half.explicit_result->displacement);
}

TEST(App, ExitCodesAndArtifact) {
  const std::string exe = std::string(SOFTSIM_BIN_DIR) + "/dhd_sim";
  if (!fs::exists(exe)) GTEST_SKIP() << "dhd_sim is not built";
  Scratch s("app");
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);
  io::Provenance prov;
  prov.tool = "test";
  io::write_artifact(s.path("mesh.json"), io::kMeshSchema, io::kMeshSchemaVersion, prov, io::mesh_to_json(m));
  const double dt_cr = dynamics::critical_time_step(m, kPaper).dt;
  nlohmann::json cfg = {{"mesh", s.path("mesh.json")},
                        {"boundary", {{"fixed", {"bottom"}}, {"prescribed", {{{"set", "top"}, {"displacement", {0, 0, -0.002}}}}}}},
                        {"solver", {{"steps", 50}}},
                        {"output", {{"vtu", s.path("final.vtu")}, {"vtu_interval", 25}}}};
  write_json(s.path("ok.json"), cfg);
  ASSERT_EQ(run_dhd_sim(s.path("ok.json"), s.path("ok_out.json")), 0);
  const io::Artifact a = io::Artifact::read(s.path("ok_out.json"), "dhd_result", 1);
  EXPECT_EQ(a.payload().at("displacement").size(), static_cast<std::size_t>(m.num_nodes()));
  EXPECT_EQ(a.payload().at("element_kind").size(), static_cast<std::size_t>(m.num_tets()));
  for (const char* f : {"final.vtu", "final_000000.vtu", "final_000025.vtu", "final_000050.vtu"})
    EXPECT_TRUE(fs::exists(s.path(f))) << f;
  // The series lists each snapshot, by its name beside the .pvd, at its simulated time: n dt
  // at a constant step, the sum of the steps taken once the step is re-estimated (the sudden 10 %
  // push compresses the top elements enough for that).
  const std::string pvd = io::read_text_file(s.path("final.pvd"));
  const double dt = a.payload().at("solver").get_double("dt");
  const auto history = a.payload().at("solver").at("dt_history").raw();
  ASSERT_GE(history.size(), 1u);
  EXPECT_EQ(history[0][2].get<double>(), dt);
  const auto time_at = [&](int step) {
    std::size_t k = 0;
    while (k + 1 < history.size() && history[k + 1][0].get<int>() <= step) ++k;
    return history[k][1].get<double>() + (step - history[k][0].get<int>()) * history[k][2].get<double>();
  };
  std::size_t at = 0;
  for (const int step : {0, 25, 50}) {
    at = pvd.find("<DataSet timestep=\"", at);
    ASSERT_NE(at, std::string::npos) << pvd;
    at += 19;
    EXPECT_EQ(std::strtod(pvd.c_str() + at, nullptr), time_at(step)) << pvd;
    char file[32];
    std::snprintf(file, sizeof file, "file=\"final_%06d.vtu\"", step);
    EXPECT_EQ(pvd.find(file, at), pvd.find("file=", at)) << pvd;
  }
  EXPECT_EQ(pvd.find("<DataSet", at), std::string::npos) << "three snapshots";
  // The final state reads back as a mesh (inline base64 by default).
  EXPECT_EQ(mesh::read_vtu(io::read_text_file(s.path("final.vtu")), "final.vtu").nodes, m.nodes);
  EXPECT_EQ(a.document().at("provenance").at("inputs").size(), 1u);

  cfg["output"] = nlohmann::json::object();
  cfg["solver"] = {{"steps", 400}, {"dt", 5 * dt_cr}};
  write_json(s.path("refused.json"), cfg);
  EXPECT_EQ(run_dhd_sim(s.path("refused.json"), s.path("refused_out.json")), 2);
  EXPECT_FALSE(fs::exists(s.path("refused_out.json")));

  cfg["solver"]["force_dt"] = true;
  write_json(s.path("forced.json"), cfg);
  EXPECT_EQ(run_dhd_sim(s.path("forced.json"), s.path("forced_out.json")), 3);
  EXPECT_FALSE(fs::exists(s.path("forced_out.json")));

  cfg["solver"] = {{"kind", "static"}};
  write_json(s.path("static.json"), cfg);
  ASSERT_EQ(run_dhd_sim(s.path("static.json"), s.path("static_out.json")), 0);
  const io::Artifact st = io::Artifact::read(s.path("static_out.json"), "dhd_result", 1);
  EXPECT_EQ(st.payload().at("solver").at("kind").as_string(), "static");
  // The static solve is timed like the explicit loop (issue 25): a Newton solve takes time.
  EXPECT_GT(st.payload().at("timing").get_double("solve_seconds"), 0.0);
  EXPECT_GE(st.payload().at("timing").get_double("setup_seconds"), 0.0);
}

TEST(Bench, MeasuresEveryPartitionAndThreadCount) {
  // Structure only (timings are for bench_dhd): uniform TLED, linear, corotational and each
  // requested linear share, for each thread count.
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);
  const nlohmann::json j = {{"mesh", "m"}, {"bench", {{"steps", 10}, {"threads", {1, 2}}, {"linear_fraction", {0.2, 0.5}}}}};
  const auto runs = hybrid::run_bench(m, parse(j, m));
  ASSERT_EQ(runs.size(), 10u);
  std::set<std::string> names;
  for (const auto& r : runs) {
    names.insert(r.partition);
    EXPECT_EQ(r.steps, 10);
    EXPECT_GT(r.steps_per_second, 0.0);
  }
  EXPECT_EQ(names, (std::set<std::string>{"all_tled", "all_linear", "all_corotational", "linear_fraction"}));
  EXPECT_DOUBLE_EQ(runs.back().linear_fraction, 0.5);
  EXPECT_EQ(runs.back().threads, 2);
  EXPECT_GT(runs.back().ns_per_element[0], 0.0);
  EXPECT_GT(runs.back().ns_per_element[1], 0.0);
}

// ---- the scene object: the same config, stepped by the caller ----

TEST(Scene, SteppedFromTheConfigEqualsTheExecutablesRun) {
  const auto m = std::make_shared<const mesh::TetMesh>(cuboid(3, 3, 3, 0.03, 0.03, 0.03));
  const nlohmann::json j = {
      {"mesh", "m"},
      {"partition", {{"linear_fraction", 0.4}}},
      {"damping", {{"alpha", 4.0}}},
      {"boundary",
       {{"fixed", {"bottom"}},
        {"prescribed", {{{"set", "top"}, {"displacement", {0, 0.0005, -0.002}}, {"ramp_time", 0.03}}}}}},
      {"solver", {{"steps", 90}, {"energy_interval", 10}}}};
  const hybrid::DhdConfig config = parse(j, *m);
  const auto whole = hybrid::run_dhd(*m, config);
  hybrid::DhdScene scene(m, config);
  EXPECT_EQ(scene.dt(), whole.step.dt);
  for (int k = 0; k < 9; ++k) scene.step(10);
  EXPECT_DOUBLE_EQ(scene.time(), 90 * scene.dt());
  const auto& r = *whole.explicit_result;
  EXPECT_EQ(r.displacement, std::vector<double>(scene.displacement(), scene.displacement() + 3 * m->num_nodes()));
  EXPECT_EQ(r.reactions, scene.reactions());
  ASSERT_EQ(r.energies.size(), scene.energies().size());
  EXPECT_EQ(r.energies.back().strain, scene.energies().back().strain);
}

TEST(Scene, ConstraintsByNameProbeByPositionAndStaticConfigs) {
  const auto m = std::make_shared<const mesh::TetMesh>(cuboid(3, 3, 3, 0.03, 0.03, 0.03));
  nlohmann::json j = {{"mesh", "m"},
                      {"boundary",
                       {{"fixed", {"bottom"}},
                        {"probe", {{"nearest", {0.03, 0.01, 0.02}}, {"stiffness", 20.0}, {"displacement", {0, 0, 0}}}}}},
                      {"solver", {{"steps", 10}}}};
  hybrid::DhdScene scene(m, parse(j, *m));
  EXPECT_EQ(scene.constraint_index("fixed bottom"), 0);
  try {
    scene.constraint_index("top");
    ADD_FAILURE() << "an unknown constraint name was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("\"fixed bottom\""), std::string::npos) << e.what();
  }
  const int node = dynamics::nearest_node(*m, Eigen::Vector3d(0.03, 0.01, 0.02));
  EXPECT_EQ(scene.probe_position(), m->nodes[node]);
  const Eigen::Vector3d tip = m->nodes[node] + Eigen::Vector3d(0.001, 0, 0);
  scene.set_probe_position(tip);
  EXPECT_EQ(scene.probe_position(), tip);
  // The body at rest and the tip 1 mm out: the force read is the spring's, k · 1 mm along x.
  EXPECT_TRUE(scene.probe_force().isApprox(Eigen::Vector3d(20.0 * 0.001, 0, 0), 1e-12));
  scene.step(5);
  EXPECT_GT(scene.displacement()[3 * node], 0.0);  // pulled towards the tip

  j["solver"] = {{"kind", "static"}};
  hybrid::DhdScene still(m, parse(j, *m));
  EXPECT_THROW(still.step(1), InputError);
  EXPECT_EQ(still.solve_static().displacement.size(), 3u * m->num_nodes());
}

// ---- the explicit step under large deformation (issue 25) ----

TEST(StableStep, DeformedEstimateFollowsTheGeometryOfNonlinearElementsOnly) {
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  const double h0 = dynamics::critical_time_step(m, kPaper).dt;
  const std::vector<char> all(m.num_tets(), 1), none(m.num_tets(), 0);
  const dynamics::DeformedCriticalStep tled(m, all, kPaper), linear(m, none, kPaper);
  std::vector<double> zero(3 * m.num_nodes(), 0.0);
  EXPECT_NEAR(tled.at(zero.data()).dt, h0, 1e-12 * h0);
  // Uniaxial compression by 20 % in z: the altitudes shrink, by at most the factor 0.8.
  std::vector<double> squeeze(3 * m.num_nodes(), 0.0), stretch(3 * m.num_nodes(), 0.0), turn(3 * m.num_nodes(), 0.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (int i = 0; i < m.num_nodes(); ++i) {
    squeeze[3 * i + 2] = -0.2 * m.nodes[i].z();
    stretch[3 * i + 2] = 0.2 * m.nodes[i].z();
    const Eigen::Vector3d x = R * m.nodes[i] - m.nodes[i];
    for (int k = 0; k < 3; ++k) turn[3 * i + k] = x[k];
  }
  const double squeezed = tled.at(squeeze.data()).dt;
  EXPECT_LT(squeezed, 0.99 * h0);
  EXPECT_GE(squeezed, 0.8 * h0 * (1 - 1e-12));
  EXPECT_GE(tled.at(stretch.data()).dt, h0 * (1 - 1e-12));  // a stretch does not shorten it
  EXPECT_NEAR(tled.at(turn.data()).dt, h0, 1e-9 * h0);      // a rigid rotation changes nothing
  // Small-strain (and corotational) stiffness does not follow the deformation: nor does its limit.
  EXPECT_EQ(linear.at(squeeze.data()).dt, h0);
  // An inverted element leaves no positive step.
  std::vector<double> flip(3 * m.num_nodes(), 0.0);
  for (int i = 0; i < m.num_nodes(); ++i) flip[3 * i + 2] = -2.0 * m.nodes[i].z();
  EXPECT_EQ(tled.at(flip.data()).dt, 0.0);
}

// A cantilever (10 × 2 × 2 cells, 0.1 m long) hanging under its own weight deflects by about 80 %
// of its length. At the default automatic step (0.9 Δt_cr of the undeformed mesh) the bending
// flattens the elements near the clamp until the step exceeds their limit; re-estimated on the
// deformed mesh, the step shrinks in time and the damped run settles on the static solution.
TEST(Run, CantileverUnderGravityAtTheDefaultStepSettlesOnTheStaticSolution) {
  const auto m = cuboid(10, 2, 2, 0.1, 0.02, 0.02);
  nlohmann::json j = {{"mesh", "m"},
                      {"material", {{"E", 10000}, {"nu", 0.35}, {"density", 1000}}},
                      {"damping", {{"alpha", 5.0}}},
                      {"boundary", {{"fixed", {"x_min"}}, {"gravity", {0, 0, -9.81}}}},
                      {"solver", {{"steps", 30000}}}};
  const auto dynamic = hybrid::run_dhd(m, parse(j, m));
  const auto& r = *dynamic.explicit_result;
  ASSERT_GT(r.step_history.size(), 1u) << "the step was re-estimated";
  EXPECT_EQ(r.step_history.front().dt, dynamic.step.dt);
  for (std::size_t k = 1; k < r.step_history.size(); ++k) {
    EXPECT_LT(r.step_history[k].dt, r.step_history[k - 1].dt);  // it only shrinks
    EXPECT_GT(r.step_history[k].first_step, r.step_history[k - 1].first_step);
  }
  EXPECT_LT(r.time, r.steps * r.dt);

  nlohmann::json st = j;
  st.erase("damping");
  st["solver"] = {{"kind", "static"}, {"increments", 20}};
  const auto equilibrium = hybrid::run_dhd(m, parse(st, m));
  const int tip = 10;  // node (10, 0, 0): the free end's lower edge
  const Eigen::Vector3d u_dyn(&r.displacement[3 * tip]), u_st(&equilibrium.static_result->displacement[3 * tip]);
  EXPECT_GT(u_st.norm(), 0.5 * 0.1) << "a large deflection";
  // Settled: e^{−α t / 2} of the initial transient is below 1e-9 after t ≈ 17 s.
  EXPECT_LT((u_dyn - u_st).norm(), 1e-7 * u_st.norm()) << u_dyn.transpose() << " vs " << u_st.transpose();

  // Without the re-estimate the same run fails, and says it is the step that failed.
  j["solver"]["dt_check_interval"] = 0;
  try {
    hybrid::run_dhd(m, parse(j, m));
    ADD_FAILURE() << "the constant step survived";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("step-size failure"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("exceeds the critical step"), std::string::npos) << e.what();
  }
  // A fixed step has nothing to re-estimate.
  j["solver"] = {{"dt", 1e-4}, {"dt_check_interval", 10}};
  EXPECT_THROW(parse(j, m), InputError);
}

// ---- what a run says about itself, and where it reads its mesh (issue 25) ----

TEST(App, MaterialFormIsRecordedAndMeshPathIsReadBesideTheConfig) {
  const std::string exe = std::string(SOFTSIM_BIN_DIR) + "/dhd_sim";
  if (!fs::exists(exe)) GTEST_SKIP() << "dhd_sim is not built";
  Scratch s("paths");
  fs::create_directories(s.dir / "scene");
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  io::Provenance prov;
  prov.tool = "test";
  io::write_artifact(s.path("scene/mesh.json"), io::kMeshSchema, io::kMeshSchemaVersion, prov, io::mesh_to_json(m));
  // "mesh.json" beside the config, run from another working directory (the build tree's).
  nlohmann::json cfg = {{"mesh", "mesh.json"},
                        {"boundary", {{"fixed", {"bottom"}}, {"prescribed", {{{"set", "top"}, {"displacement", {0, 0, -0.001}}}}}}},
                        {"solver", {{"kind", "static"}}}};
  write_json(s.path("scene/run.json"), cfg);
  ASSERT_EQ(run_dhd_sim(s.path("scene/run.json"), s.path("out.json")), 0);
  const io::Artifact a = io::Artifact::read(s.path("out.json"), "dhd_result", 1);
  // The neo-Hookean form is named, and so is the fact that the config left it to the default.
  EXPECT_EQ(a.payload().at("material").at("model").as_string(), "neo_hookean_paper");
  EXPECT_TRUE(a.payload().at("material").at("model_defaulted").raw().get<bool>());
  cfg["material"] = {{"model", "neo_hookean_decoupled"}};
  write_json(s.path("scene/run.json"), cfg);
  ASSERT_EQ(run_dhd_sim(s.path("scene/run.json"), s.path("out2.json")), 0);
  const io::Artifact b = io::Artifact::read(s.path("out2.json"), "dhd_result", 1);
  EXPECT_EQ(b.payload().at("material").at("model").as_string(), "neo_hookean_decoupled");
  EXPECT_FALSE(b.payload().at("material").at("model_defaulted").raw().get<bool>());

  // A mesh in neither folder: exit 2, and the message names the field and the config's folder.
  cfg["mesh"] = "no_such_mesh.json";
  write_json(s.path("scene/bad.json"), cfg);
  const std::string cmd = exe + " --config " + s.path("scene/bad.json") + " --out " + s.path("bad_out.json") + " 2> " +
                          s.path("bad_err.txt");
  EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 2);
  const std::string err = io::read_text_file(s.path("bad_err.txt"));
  EXPECT_NE(err.find("/mesh"), std::string::npos) << err;
  EXPECT_NE(err.find((s.dir / "scene").string()), std::string::npos) << err;
  EXPECT_NE(err.find("working directory"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(s.path("bad_out.json")));
}

TEST(Config, MaterialModelDefaultIsFlagged) {
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  EXPECT_TRUE(parse({{"mesh", "m"}}, m).model_defaulted);
  EXPECT_TRUE(parse({{"mesh", "m"}, {"material", {{"E", 4000}}}}, m).model_defaulted);
  EXPECT_FALSE(parse({{"mesh", "m"}, {"material", {{"model", "neo_hookean_paper"}}}}, m).model_defaulted);
}

TEST(Output, DisplacementFieldIsWrittenUnlessTheConfigLeavesItOut) {
  const auto m = cuboid(3, 3, 2, 0.03, 0.03, 0.02);
  nlohmann::json j = {
      {"mesh", "m"},
      {"boundary", {{"fixed", {"bottom"}}, {"prescribed", {{{"set", "top"}, {"displacement", {0, 0, -0.001}}}}}}},
      {"solver", {{"steps", 20}}},
      {"output", {{"trajectories", {{{"set", "top"}}}}, {"trajectory_interval", 5}}}};
  const hybrid::DhdConfig full_cfg = parse(j, m);
  EXPECT_TRUE(full_cfg.output.displacement);  // the default keeps the field
  const hybrid::DhdRun run = hybrid::run_dhd(m, full_cfg);
  const nlohmann::json full = hybrid::result_payload(m, full_cfg, run);
  ASSERT_TRUE(full.contains("displacement"));
  EXPECT_EQ(full.at("displacement").size(), static_cast<std::size_t>(m.num_nodes()));

  j["output"]["displacement"] = false;
  const hybrid::DhdConfig lean_cfg = parse(j, m);
  const nlohmann::json lean = hybrid::result_payload(m, lean_cfg, run);
  EXPECT_FALSE(lean.contains("displacement"));
  // Everything else a stage reads is still there and unchanged: trajectories, reactions, solver.
  EXPECT_EQ(lean.at("trajectories"), full.at("trajectories"));
  EXPECT_EQ(lean.at("reactions"), full.at("reactions"));
  EXPECT_EQ(lean.at("solver"), full.at("solver"));
  nlohmann::json stripped = full;
  stripped.erase("displacement");
  stripped.erase("timing");
  nlohmann::json lean_cmp = lean;
  lean_cmp.erase("timing");
  EXPECT_EQ(lean_cmp, stripped);

  j["output"]["displacement"] = "no";
  EXPECT_THROW(parse(j, m), InputError);
}

// ---- 000 §2.2.2's condition on small-strain elements (SmallStrainCheck) ----

namespace {

// u = (A − I) X at every node: the homogeneous deformation x = A X.
std::vector<double> affine_field(const mesh::TetMesh& m, const Eigen::Matrix3d& A) {
  std::vector<double> u(3 * m.num_nodes());
  for (int a = 0; a < m.num_nodes(); ++a) {
    const Eigen::Vector3d d = (A - Eigen::Matrix3d::Identity()) * m.nodes[a];
    for (int k = 0; k < 3; ++k) u[3 * a + k] = d[k];
  }
  return u;
}

}  // namespace

// A rigid rotation breaks a linear element (‖R − I‖₂ = 2 sin(θ/2)) and leaves a corotational
// one untouched (E = 0); a uniform stretch λ gives λ − 1 and (λ² − 1)/2 respectively; TLED
// and ANP elements are not watched.
TEST(SmallStrainCheck, MeasuresFollowTheKindsHomogeneousDeformations) {
  const auto m = cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  const double theta = 0.5;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(theta, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d S = Eigen::Vector3d(1.05, 1.0, 1.0).asDiagonal();
  auto check_all = [&](ElementKind kind, const Eigen::Matrix3d& A) {
    hybrid::SmallStrainCheck c(m, std::vector<ElementKind>(m.num_tets(), kind));
    c.observe(affine_field(m, A).data(), 0.25);
    return c.record();
  };
  const auto lin_rot = check_all(ElementKind::linear, R);
  EXPECT_NEAR(lin_rot.largest, 2 * std::sin(theta / 2), 1e-12);
  EXPECT_TRUE(lin_rot.broken());
  EXPECT_DOUBLE_EQ(lin_rot.time, 0.25);
  EXPECT_EQ(lin_rot.elements, m.num_tets());
  EXPECT_LT(check_all(ElementKind::corotational, R).largest, 1e-12);
  EXPECT_NEAR(check_all(ElementKind::linear, S).largest, 0.05, 1e-12);
  EXPECT_NEAR(check_all(ElementKind::corotational, S).largest, 0.5 * (1.05 * 1.05 - 1), 1e-12);
  EXPECT_FALSE(check_all(ElementKind::linear, S).broken());
  const auto tled = check_all(ElementKind::tled, R);
  EXPECT_EQ(tled.elements, 0);
  EXPECT_EQ(tled.element, -1);
}

// The bound that skips most eigenvalue solves changes nothing: the record equals the largest
// of element_strain over the watched elements, found where it is, and removed elements are
// left out.
TEST(SmallStrainCheck, EqualsTheLargestElementStrainOfTheWatchedElements) {
  const auto m = cuboid(4, 3, 3, 0.04, 0.03, 0.03);
  std::vector<ElementKind> kinds(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) kinds[e] = static_cast<ElementKind>(e % fem::kNumElementKinds);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-2e-3, 2e-3);
  std::vector<double> u(3 * m.num_nodes());
  for (double& x : u) x = d(rng);
  const auto dg = hybrid::element_strain(m, u, hybrid::StrainMeasure::displacement_gradient);
  const auto gl = hybrid::element_strain(m, u, hybrid::StrainMeasure::green_lagrange);
  for (int removed_every : {0, 3}) {
    const auto removed = [&](int e) { return removed_every && e % removed_every == 0; };
    double best = 0;
    int where = -1;
    for (int e = 0; e < m.num_tets(); ++e) {
      if (removed(e)) continue;
      const double s = kinds[e] == ElementKind::linear ? dg[e] : kinds[e] == ElementKind::corotational ? gl[e] : -1;
      if (s > best) {
        best = s;
        where = e;
      }
    }
    hybrid::SmallStrainCheck c(m, kinds);
    c.observe(u.data(), 1.0, removed);
    EXPECT_EQ(c.record().largest, best);
    EXPECT_EQ(c.record().element, where);
    EXPECT_GT(best, 0.05);
  }
}

// A run reports the condition: a hybrid cuboid pressed by 1 % of its height keeps its linear
// elements within it, pressed by 20 % it does not, and the artifact says which.
TEST(SmallStrainCheck, ARunReportsTheLargestSmallStrainDeformation) {
  const auto m = cuboid(3, 3, 3, 0.03, 0.03, 0.03);
  auto run_with = [&](double press) {
    const nlohmann::json j = {
        {"mesh", "m"},
        {"partition", {{"linear_fraction", 0.5}}},
        {"boundary", {{"fixed", {"bottom"}}, {"prescribed", {{{"set", "top"}, {"displacement", {0, 0, -press}}, {"ramp_time", 0.001}}}}}},
        {"solver", {{"steps", 200}}}};
    const auto c = parse(j, m);
    const auto run = hybrid::run_dhd(m, c);
    return std::make_pair(run.small_strain, hybrid::result_payload(m, c, run).at("small_strain_check"));
  };
  const auto [small, small_json] = run_with(0.0003);
  EXPECT_FALSE(small.broken());
  EXPECT_GT(small.largest, 0.0);
  EXPECT_GT(small.samples, 2);
  EXPECT_EQ(small_json.at("broken"), false);
  EXPECT_EQ(small_json.at("kind"), "linear");
  const auto [large, large_json] = run_with(0.006);
  EXPECT_TRUE(large.broken());
  EXPECT_EQ(large_json.at("broken"), true);
  EXPECT_DOUBLE_EQ(large_json.at("largest").get<double>(), large.largest);
  EXPECT_DOUBLE_EQ(large_json.at("limit").get<double>(), 0.10);
}
