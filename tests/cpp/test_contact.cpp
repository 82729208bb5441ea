// Rigid tools in frictionless kinematic contact (issue 23; dynamics::RigidTool,
// dynamics/explicit_contact.cpp): a plane pressed on a face is the displacement constraint on
// the face's normal component, a tool beside the body changes nothing, a tool moved between
// steps is the same tool moved by its ramp, the tool's work keeps the energy balance, the
// shapes' distances, and the config's checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "softsim/dynamics/scene.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/hybrid/dhd_run.hpp"
#include "softsim/hybrid/dhd_scene.hpp"
#include "softsim/io/errors.hpp"
#include "support/scenes.hpp"

using namespace softsim;
using test_scenes::cuboid;

namespace {

const double kSide = 0.03;

hybrid::DhdConfig parse(const nlohmann::json& j, const mesh::TetMesh& m) {
  return hybrid::read_dhd_config(io::JsonReader(j, "contact.json"), m);
}

nlohmann::json base_config(int steps, double alpha) {
  return {{"mesh", "m"},
          {"material", {{"model", "neo_hookean_decoupled"}, {"E", 5000}, {"nu", 0.35}, {"density", 1000}}},
          {"partition", {{"linear_fraction", 0.5}}},
          {"damping", {{"alpha", alpha}}},
          {"solver", {{"steps", steps}}},
          {"boundary", {{"fixed", {"bottom"}}}}};
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

TEST(RigidTool, SignedDistancesOfTheShapes) {
  dynamics::RigidTool t;
  Eigen::Vector3d n;
  t.shape = dynamics::RigidTool::Shape::sphere;
  t.radius = 0.5;
  EXPECT_DOUBLE_EQ(t.signed_distance(Eigen::Vector3d(3, 4, 0), Eigen::Vector3d::Zero(), n), 4.5);
  EXPECT_TRUE(n.isApprox(Eigen::Vector3d(0.6, 0.8, 0)));
  t.shape = dynamics::RigidTool::Shape::capsule;
  t.half_axis = Eigen::Vector3d(0, 0, 1);
  EXPECT_DOUBLE_EQ(t.signed_distance(Eigen::Vector3d(0.2, 0, 0.7), Eigen::Vector3d::Zero(), n), -0.3);  // beside the segment
  EXPECT_TRUE(n.isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_DOUBLE_EQ(t.signed_distance(Eigen::Vector3d(0, 0, 3), Eigen::Vector3d::Zero(), n), 1.5);  // beyond an end
  t.shape = dynamics::RigidTool::Shape::plane;
  t.normal = Eigen::Vector3d(0, 0, -1);
  EXPECT_DOUBLE_EQ(t.signed_distance(Eigen::Vector3d(5, 5, 1.25), Eigen::Vector3d(0, 0, 2), n), 0.75);
  EXPECT_DOUBLE_EQ(t.signed_distance(Eigen::Vector3d(5, 5, 2.25), Eigen::Vector3d(0, 0, 2), n), -0.25);
}

// A plane pressed down on the top face is, for the top nodes, exactly a prescribed displacement
// of their z component with x and y free: the projection puts each node on the plane, which is
// the constraint's value. The runs agree to round-off all along, and once settled the force on
// the plane is the constraint's reaction on the body, reversed.
TEST(Contact, APlanePressedOnAFaceIsTheConstraintOnItsNormalComponent) {
  const auto m = cuboid(3, 3, 3, kSide, kSide, kSide);
  const double press = 0.003, ramp = 0.05;
  nlohmann::json with_plane = base_config(6000, 60.0);
  with_plane["boundary"]["tools"] = {{{"shape", "plane"},
                                      {"normal", {0, 0, -1}},
                                      {"position", {0, 0, kSide}},
                                      {"travel", {0, 0, -press}},
                                      {"ramp_time", ramp},
                                      {"ramp", "smooth"},
                                      {"nodes", "top"}}};
  nlohmann::json with_constraint = base_config(6000, 60.0);
  with_constraint["boundary"]["prescribed"] = {
      {{"set", "top"}, {"displacement", {0, 0, -press}}, {"components", "z"}, {"ramp_time", ramp}, {"ramp", "smooth"}}};
  const auto cp = parse(with_plane, m), cc = parse(with_constraint, m);
  const auto rp = hybrid::run_dhd(m, cp), rc = hybrid::run_dhd(m, cc);
  const auto& up = rp.explicit_result->displacement;
  const auto& uc = rc.explicit_result->displacement;
  ASSERT_EQ(up.size(), uc.size());
  double diff = 0;
  for (std::size_t q = 0; q < up.size(); ++q) diff = std::max(diff, std::abs(up[q] - uc[q]));
  EXPECT_LT(diff, 1e-12 * max_abs(uc));
  EXPECT_GT(max_abs(uc), 0.5 * press);
  // Every top node touches the plane at the end, and the force on the plane is the reaction.
  const auto& tool = rp.explicit_result->tool_force.at(0);
  const int top = static_cast<int>(m.node_sets.at("top").size());
  EXPECT_EQ(rp.explicit_result->tool_contacts.at(0).back(), top);
  const Eigen::Vector3d reaction = rc.explicit_result->reactions.at(1);  // "prescribed top", on the body
  EXPECT_LT(reaction.z(), 0.0);  // the plate pushes the body down
  EXPECT_NEAR(tool.back().z(), -reaction.z(), 1e-4 * std::abs(reaction.z()));
  EXPECT_NEAR(tool.back().x(), 0.0, 1e-9 * std::abs(reaction.z()));
}

// A tool that never reaches the body changes nothing, bit for bit, and feels no force.
TEST(Contact, AToolBesideTheBodyChangesNothing) {
  const auto m = cuboid(3, 3, 3, kSide, kSide, kSide);
  nlohmann::json plain = base_config(400, 5.0);
  plain["boundary"]["prescribed"] = {{{"set", "top"}, {"displacement", {0.001, 0, -0.002}}, {"ramp_time", 0.01}}};
  nlohmann::json with_tool = plain;
  with_tool["boundary"]["tools"] = {{{"shape", "sphere"}, {"radius", 0.005}, {"position", {0.1, 0.1, 0.1}},
                                     {"travel", {0.01, 0, 0}}, {"ramp_time", 0.01}}};
  const auto a = hybrid::run_dhd(m, parse(plain, m)), b = hybrid::run_dhd(m, parse(with_tool, m));
  EXPECT_EQ(a.explicit_result->displacement, b.explicit_result->displacement);
  for (const auto& f : b.explicit_result->tool_force.at(0)) EXPECT_EQ(f, Eigen::Vector3d::Zero());
}

// The haptic loop moves a tool between steps: setting its position before every step to where
// its ramp would have put it gives the same run, bit for bit. Undamped, the sphere's work is the
// body's kinetic + strain energy: the projection loses only what the node's normal velocity
// relative to the tool carries at each new contact (a slow tool: little).
TEST(Contact, AToolMovedBetweenStepsIsTheRampedToolAndItsWorkBalancesTheEnergy) {
  const auto m = cuboid(8, 8, 3, 0.04, 0.04, kSide);
  const double radius = 0.01, depth = 0.003, ramp = 0.1;
  nlohmann::json j = base_config(300, 0.0);
  j["boundary"]["tools"] = {{{"shape", "sphere"}, {"radius", radius}, {"position", {0.02, 0.02, kSide + radius}},
                             {"travel", {0, 0, -depth}}, {"ramp_time", ramp}, {"ramp", "smooth"}}};
  const auto c = parse(j, m);
  hybrid::DhdScene ramped(std::shared_ptr<const mesh::TetMesh>(&m, [](const mesh::TetMesh*) {}), c);
  hybrid::DhdScene moved(std::shared_ptr<const mesh::TetMesh>(&m, [](const mesh::TetMesh*) {}), c);
  const auto& tool = c.scene.tools.at(0);
  for (int s = 0; s < 300; ++s) {
    ramped.step();
    // Where the ramped tool is at the end of step s (t_s + Δt, as the engine evaluates it).
    moved.solver().set_tool_position(0, tool.centre(moved.solver().time_at(s) + moved.solver().step_size(s)));
    moved.step();
  }
  ASSERT_GT(ramped.time(), ramp);
  ASSERT_GE(ramped.solver().tool_contacts(0), 3);  // of the centre node and its four neighbours (5 mm apart)
  for (int q = 0; q < 3 * m.num_nodes(); ++q) ASSERT_EQ(ramped.displacement()[q], moved.displacement()[q]) << q;
  EXPECT_EQ(ramped.solver().tool_force(0), moved.solver().tool_force(0));
  EXPECT_GT(ramped.solver().tool_force(0).z(), 0.0);  // the body pushes the tool up
  const auto& e = ramped.energies().back();
  EXPECT_GT(e.external_work, 0.0);
  // The projection is a nodal force in eq. 33, booked as one: the central-difference energy
  // identity holds for it as for a load (exactly for linear elements, to O(Δt²) for TLED).
  EXPECT_LT(std::abs(e.dissipated), 1e-4 * e.external_work);
}

TEST(Contact, BadToolsAreInputErrorsNamingThePointer) {
  const auto m = cuboid(2, 2, 2, kSide, kSide, kSide);
  auto error_of = [&](const nlohmann::json& tool, bool static_solver = false) {
    nlohmann::json j = base_config(10, 0.0);
    j["boundary"]["tools"] = {tool};
    if (static_solver) j["solver"] = {{"kind", "static"}};
    try {
      parse(j, m);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const nlohmann::json sphere = {{"shape", "sphere"}, {"radius", 0.01}, {"position", {0, 0, 0.05}}};
  EXPECT_EQ(error_of(sphere), "no error");
  EXPECT_NE(error_of({{"shape", "cube"}, {"position", {0, 0, 0}}}).find("/boundary/tools/0/shape"), std::string::npos);
  EXPECT_NE(error_of({{"shape", "sphere"}, {"radius", -1}, {"position", {0, 0, 0}}}).find("/boundary/tools/0/radius"),
            std::string::npos);
  EXPECT_NE(error_of({{"shape", "plane"}, {"normal", {0, 0, 0}}, {"position", {0, 0, 0}}}).find("/boundary/tools/0/normal"),
            std::string::npos);
  EXPECT_NE(error_of({{"shape", "capsule"}, {"radius", 0.01}, {"position", {0, 0, 0}}}).find("/boundary/tools/0"),
            std::string::npos);  // no axis
  nlohmann::json unknown_set = sphere;
  unknown_set["nodes"] = "nowhere";
  EXPECT_NE(error_of(unknown_set).find("/boundary/tools/0/nodes"), std::string::npos);
  nlohmann::json nan_position = sphere;
  nan_position["position"] = {0, "x", 0};
  EXPECT_NE(error_of(nan_position).find("/boundary/tools/0/position"), std::string::npos);
  nlohmann::json extra = sphere;
  extra["stickiness"] = 0.3;
  EXPECT_NE(error_of(extra).find("stickiness"), std::string::npos);
  nlohmann::json negative_friction = sphere;
  negative_friction["friction"] = -0.1;
  EXPECT_NE(error_of(negative_friction).find("/boundary/tools/0/friction"), std::string::npos);
  EXPECT_NE(error_of(sphere, true).find("/boundary/tools"), std::string::npos);
}

// Coulomb friction: a plate pressed 2 mm on the top face and then dragged 5 mm along x. With a
// large μ the face sticks to the plate: the nodes inside the face move with it exactly (the
// face's edges may lift off the plate where the block bulges). With μ = 0.3 the face slides under
// the plate while it is dragged: the lateral force never exceeds μ times the normal force (each
// node's at most its own limit) and comes within 1 % of it. Without friction there is none.
TEST(Contact, APlateDraggedOverTheFaceSticksOrSlidesByCoulomb) {
  const auto m = cuboid(3, 3, 3, kSide, kSide, kSide);
  auto drag = [&](double mu) {
    nlohmann::json j = base_config(1, 60.0);
    j["boundary"]["tools"] = {{{"shape", "plane"}, {"normal", {0, 0, -1}}, {"position", {0, 0, kSide}},
                               {"nodes", "top"}, {"friction", mu}}};
    const auto c = parse(j, m);
    hybrid::DhdScene scene(std::shared_ptr<const mesh::TetMesh>(&m, [](const mesh::TetMesh*) {}), c);
    const double press = 0.002, slide = 0.005;
    auto plate_at = [&](double t) {
      const double s = std::clamp(t / 0.1, 0.0, 1.0), r = std::clamp((t - 0.1) / 0.2, 0.0, 1.0);
      return Eigen::Vector3d(slide * r, 0, kSide - press * s * s * (3 - 2 * s));
    };
    Eigen::Vector3d mid_drag_force = Eigen::Vector3d::Zero();
    for (int s = 0; scene.time() < 0.3; ++s) {
      scene.solver().set_tool_position(0, plate_at(scene.solver().time_at(s) + scene.solver().step_size(s)));
      scene.step();
      if (mid_drag_force.isZero() && scene.time() >= 0.25) mid_drag_force = scene.solver().tool_force(0);
    }
    std::vector<double> top_x;  // of the nodes inside the top face
    for (int node : m.node_sets.at("top")) {
      const Eigen::Vector3d& X = m.nodes[node];
      if (X.x() > 1e-9 && X.x() < kSide - 1e-9 && X.y() > 1e-9 && X.y() < kSide - 1e-9)
        top_x.push_back(scene.displacement()[3 * node]);
    }
    return std::make_tuple(mid_drag_force, top_x, plate_at(scene.time()).x());
  };
  const auto [stuck_force, stuck_x, plate_x] = drag(100.0);
  ASSERT_EQ(stuck_x.size(), 4u);
  for (double x : stuck_x) EXPECT_NEAR(x, plate_x, 1e-9 * plate_x);
  const auto [sliding_force, sliding_x, plate_x2] = drag(0.3);
  EXPECT_GT(sliding_force.z(), 0.01);  // the face pushes the plate up
  EXPECT_LT(sliding_force.x(), 0.0);   // and holds it back
  EXPECT_LE(-sliding_force.x(), 0.3 * sliding_force.z() * (1 + 1e-12));
  EXPECT_GT(-sliding_force.x(), 0.99 * 0.3 * sliding_force.z());
  for (double x : sliding_x) EXPECT_LT(x, 0.9 * plate_x2);  // the face lags behind the plate
  const auto [free_force, free_x, plate_x3] = drag(0.0);
  EXPECT_NEAR(free_force.x(), 0.0, 1e-12);
}
