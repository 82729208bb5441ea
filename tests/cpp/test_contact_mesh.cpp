// A rigid tool of any shape: a closed triangle surface read from STL or OBJ (issue 23;
// mesh/closed_surface.hpp, mesh/stl_reader.hpp, dynamics::RigidTool::Shape::mesh). Its inside
// test against the winding number, its signed distance against a sphere's, a faceted sphere and
// box against the analytic sphere and plane on the same scene, bad files; and the broad phase
// (dynamics/contact_search.hpp): bit for bit the results of testing every node, while it lists
// only the nodes near the tool.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/hybrid/dhd_run.hpp"
#include "softsim/hybrid/dhd_scene.hpp"
#include "softsim/io/artifact.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/io/surface_files.hpp"
#include "softsim/mesh/closed_surface.hpp"
#include "softsim/mesh/stl_reader.hpp"
#include "support/input_error.hpp"
#include "support/scenes.hpp"

using namespace softsim;
using test_scenes::cuboid;
namespace fs = std::filesystem;

namespace {

// An icosahedron subdivided `level` times, its vertices on the sphere of `radius` about the origin.
mesh::TriangleSurface icosphere(int level, double radius) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  mesh::TriangleSurface s;
  for (const auto& v : std::vector<Eigen::Vector3d>{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}})
    s.vertices.push_back(v.normalized());
  s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto middle = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      s.vertices.push_back((s.vertices[a] + s.vertices[b]).normalized());
      return mid[key] = static_cast<int>(s.vertices.size()) - 1;
    };
    std::vector<mesh::Triangle> next;
    for (const auto& tri : s.triangles) {
      const int ab = middle(tri[0], tri[1]), bc = middle(tri[1], tri[2]), ca = middle(tri[2], tri[0]);
      next.insert(next.end(), {{tri[0], ab, ca}, {tri[1], bc, ab}, {tri[2], ca, bc}, {ab, bc, ca}});
    }
    s.triangles = next;
  }
  for (auto& v : s.vertices) v *= radius;
  return s;
}

// The box [lo, hi], two triangles a face, outward.
mesh::TriangleSurface box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  mesh::TriangleSurface s;
  for (int k = 0; k < 8; ++k) s.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  s.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return s;
}

std::string ascii_stl(const mesh::TriangleSurface& s) {
  std::ostringstream out;
  out.precision(17);
  out << "solid tool\n";
  for (const auto& tri : s.triangles) {
    out << "  facet normal 0 0 0\n    outer loop\n";
    for (int v : tri) out << "      vertex " << s.vertices[v].x() << ' ' << s.vertices[v].y() << ' ' << s.vertices[v].z() << '\n';
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid tool\n";
  return out.str();
}

std::string binary_stl(const mesh::TriangleSurface& s) {
  std::string bytes(80, ' ');
  const std::uint32_t n = static_cast<std::uint32_t>(s.triangles.size());
  bytes.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& tri : s.triangles) {
    float rec[12] = {0, 0, 0};
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) rec[3 + 3 * c + k] = static_cast<float>(s.vertices[tri[c]][k]);
    bytes.append(reinterpret_cast<const char*>(rec), sizeof rec);
    bytes.append(2, '\0');
  }
  return bytes;
}

struct Scratch {
  fs::path dir;
  explicit Scratch(const std::string& name) : dir(fs::path(SOFTSIM_BIN_DIR) / ".." / ("test_contact_mesh_" + name)) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Scratch() { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return (dir / name).string();
  }
};

hybrid::DhdConfig parse(const nlohmann::json& j, const mesh::TetMesh& m) {
  return hybrid::read_dhd_config(io::JsonReader(j, "contact.json"), m);
}

nlohmann::json base_config(int steps, double alpha) {
  return {{"mesh", "m"},
          {"material", {{"model", "neo_hookean_decoupled"}, {"E", 5000}, {"nu", 0.35}, {"density", 1000}}},
          {"damping", {{"alpha", alpha}}},
          {"solver", {{"steps", steps}}},
          {"boundary", {{"fixed", {"bottom"}}}}};
}

std::shared_ptr<const mesh::TetMesh> borrowed(const mesh::TetMesh& m) {
  return std::shared_ptr<const mesh::TetMesh>(&m, [](const mesh::TetMesh*) {});
}

}  // namespace

TEST(StlReader, AsciiAndBinaryGiveTheSurfaceWithSharedCornersWelded) {
  const auto s = box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 0.5));
  for (const auto& read : {mesh::read_stl(ascii_stl(s), "a.stl"), mesh::read_stl(binary_stl(s), "b.stl")}) {
    ASSERT_EQ(read.vertices.size(), 8u);
    ASSERT_EQ(read.triangles.size(), 12u);
    const mesh::ClosedSurface solid(read, "box.stl");
    EXPECT_NEAR(solid.volume(), 1.0, 1e-12);
  }
}

TEST(StlReader, MalformedFilesAreInputErrorsNamingTheFile) {
  const auto s = box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  using test_support::input_error_of;
  const std::string ascii = ascii_stl(s);
  EXPECT_NE(input_error_of([&] { mesh::read_stl("solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0\n", "t.stl"); })
                .find("t.stl: line 4"),
            std::string::npos);
  const std::string cut = ascii.substr(0, ascii.rfind("outer loop") + 10);  // ends inside a facet
  EXPECT_NE(input_error_of([&] { mesh::read_stl(cut, "t.stl"); }).find("t.stl: line"), std::string::npos);
  const std::string binary = binary_stl(s);
  EXPECT_NE(input_error_of([&] { mesh::read_stl(binary.substr(0, binary.size() - 7), "t.stl"); }).find("t.stl: expected an STL"),
            std::string::npos);  // truncated
  EXPECT_NE(input_error_of([&] { mesh::read_stl("solid empty\nendsolid empty\n", "t.stl"); }).find("no triangles"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { mesh::read_stl("solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 nan\n", "t.stl"); })
                .find("finite"),
            std::string::npos);
}

// Closed, consistently oriented, not degenerate: anything else is refused; an inward surface is turned.
TEST(ClosedSurface, RefusesOpenOrInconsistentSurfacesAndTurnsAnInwardOne) {
  using test_support::input_error_of;
  auto s = box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  auto open = s;
  open.triangles.pop_back();
  EXPECT_NE(input_error_of([&] { mesh::ClosedSurface(open, "open.stl"); }).find("open.stl: expected a closed surface"),
            std::string::npos);
  auto flipped = s;
  std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
  EXPECT_NE(input_error_of([&] { mesh::ClosedSurface(flipped, "f.stl"); }).find("consistently oriented"), std::string::npos);
  auto doubled = s;
  doubled.triangles.push_back(s.triangles[0]);
  EXPECT_NE(input_error_of([&] { mesh::ClosedSurface(doubled, "d.stl"); }).find("d.stl"), std::string::npos);
  auto flat = s;
  for (auto& v : flat.vertices) v.z() = 0;
  EXPECT_NE(input_error_of([&] { mesh::ClosedSurface(flat, "z.stl"); }).find("z.stl"), std::string::npos);
  auto inward = s;
  for (auto& tri : inward.triangles) std::swap(tri[1], tri[2]);
  const mesh::ClosedSurface turned(inward, "in.stl");
  EXPECT_NEAR(turned.volume(), 1.0, 1e-12);
  Eigen::Vector3d n;
  EXPECT_NEAR(turned.signed_distance(Eigen::Vector3d(0.5, 0.5, 0.9), n), -0.1, 1e-15);
  EXPECT_TRUE(n.isApprox(Eigen::Vector3d::UnitZ()));
}

// Inside or outside by the pseudo-normal at the nearest point agrees with the winding number
// everywhere, on a non-convex (star-shaped) surface, for random points and for points just
// inside and just outside its vertices and edges, where a face normal alone would fail.
TEST(ClosedSurface, InsideTestAgreesWithTheWindingNumberAtFacesEdgesAndVertices) {
  auto s = icosphere(2, 1.0);
  for (std::size_t v = 0; v < s.vertices.size(); ++v) s.vertices[v] *= v % 3 == 0 ? 1.5 : 1.0;  // spikes: non-convex
  const mesh::ClosedSurface solid(s, "star");
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.6, 1.6);
  int inside = 0;
  auto check = [&](const Eigen::Vector3d& x) {
    Eigen::Vector3d n;
    const double d = solid.signed_distance(x, n);
    const double w = solid.winding_number(x);
    ASSERT_TRUE(std::abs(w) < 1e-9 || std::abs(w - 1) < 1e-9) << w;
    ASSERT_EQ(d < 0, w > 0.5) << x.transpose() << " d = " << d << " w = " << w;
    ASSERT_NEAR(n.norm(), 1.0, 1e-12);
    inside += d < 0;
  };
  for (int k = 0; k < 3000; ++k) check(Eigen::Vector3d(u(rng), u(rng), u(rng)));
  EXPECT_GT(inside, 300);
  for (const auto& tri : s.triangles)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d vertex = s.vertices[tri[c]], edge = 0.5 * (s.vertices[tri[c]] + s.vertices[tri[(c + 1) % 3]]);
      for (double f : {1 - 1e-7, 1 + 1e-7}) {  // star-shaped about the origin: scaling crosses the surface once
        check(f * vertex);
        check(f * edge);
      }
    }
}

// The faceted sphere's signed distance is the sphere's to within the faceting (the largest gap
// between the sphere and a flat face, R (1 − cos θ) with θ the face's angular radius), which
// falls about fourfold per subdivision.
TEST(ClosedSurface, SignedDistanceOfAFacetedSphereConvergesToTheSphere) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  double previous = 1e300;
  for (int level = 2; level <= 5; ++level) {
    const mesh::ClosedSurface solid(icosphere(level, 1.0), "sphere");
    double worst = 0;
    for (int k = 0; k < 500; ++k) {
      const Eigen::Vector3d x(u(rng), u(rng), u(rng));
      Eigen::Vector3d n;
      const double d = solid.signed_distance(x, n);
      worst = std::max(worst, std::abs(d - (x.norm() - 1.0)));
      if (x.norm() > 0.3) EXPECT_GT(n.dot(x.normalized()), 0.9);
    }
    EXPECT_LT(worst, 0.3 * previous + 1e-12) << "level " << level;
    EXPECT_LT(worst, 1.0 / std::pow(4.0, level)) << "level " << level;
    previous = worst;
  }
}

// The same press with the analytic sphere and with faceted spheres of 1280, 5120 and 20480
// triangles (inscribed: their faces lie up to R (1 − cos θ) inside the sphere): while the
// sphere is pushed 3 mm in and held, the force on the faceted tool approaches the sphere's as
// the facets shrink, within 0.5 % on average on the finest. (Held longer, the kinematic contact
// of either tool settles into a small chatter of the nodes at the rim of the patch, which
// would hide the faceting.) A faceted box larger than the face pressed flat is the plane, to
// round-off.
TEST(MeshTool, FacetedSphereAndBoxAgreeWithTheAnalyticSphereAndPlane) {
  const auto m = cuboid(16, 16, 6, 0.04, 0.04, 0.03);
  const double radius = 0.01, depth = 0.003;
  nlohmann::json j = base_config(500, 60.0);
  j["solver"]["energy_interval"] = 50;
  j["boundary"]["tools"] = {{{"shape", "sphere"}, {"radius", radius}, {"position", {0.02, 0.02, 0.03 + radius}},
                             {"travel", {0, 0, -depth}}, {"ramp_time", 0.1}, {"ramp", "smooth"}}};
  const auto analytic = parse(j, m);
  const auto reference = hybrid::run_dhd(m, analytic).explicit_result->tool_force.at(0);
  ASSERT_GT(reference.back().z(), 0.1);
  double previous = 1e300;
  for (int level = 3; level <= 5; ++level) {
    auto c = analytic;
    c.scene.tools[0].shape = dynamics::RigidTool::Shape::mesh;
    c.scene.tools[0].surface = std::make_shared<const mesh::ClosedSurface>(icosphere(level, radius), "sphere");
    const auto f = hybrid::run_dhd(m, c).explicit_result->tool_force.at(0);
    ASSERT_EQ(f.size(), reference.size());
    double error = 0;
    for (std::size_t k = 1; k < f.size(); ++k) {
      error += std::abs(f[k].z() - reference[k].z()) / reference[k].z() / static_cast<double>(f.size() - 1);
      EXPECT_LT(std::abs(f[k].x()) + std::abs(f[k].y()), 0.02 * reference.back().z());
    }
    EXPECT_LT(error, 0.5 * previous) << "level " << level;
    previous = error;
  }
  EXPECT_LT(previous, 0.005);

  nlohmann::json p = base_config(800, 60.0);
  p["boundary"]["tools"] = {{{"shape", "plane"}, {"normal", {0, 0, -1}}, {"position", {0, 0, 0.03}},
                             {"travel", {0, 0, -depth}}, {"ramp_time", 0.05}, {"ramp", "smooth"}, {"nodes", "top"}}};
  const auto plane = parse(p, m);
  auto boxed = plane;
  boxed.scene.tools[0].shape = dynamics::RigidTool::Shape::mesh;
  boxed.scene.tools[0].surface = std::make_shared<const mesh::ClosedSurface>(
      box(Eigen::Vector3d(-0.03, -0.03, 0), Eigen::Vector3d(0.07, 0.07, 0.05)), "box");
  const auto a = hybrid::run_dhd(m, plane), b = hybrid::run_dhd(m, boxed);
  const double scale = depth;
  for (std::size_t q = 0; q < a.explicit_result->displacement.size(); ++q)
    ASSERT_NEAR(a.explicit_result->displacement[q], b.explicit_result->displacement[q], 1e-12 * scale) << q;
  const auto fa = a.explicit_result->tool_force.at(0).back(), fb = b.explicit_result->tool_force.at(0).back();
  EXPECT_NEAR(fa.z(), fb.z(), 1e-9 * fa.z());
}

// From the config: a .stl or .obj file, scaled, relative to the config's folder; bad files are
// bad input naming the config, the member and the file.
TEST(MeshTool, ConfigReadsStlAndObjFilesAndNamesBadOnes) {
  Scratch dir("config");
  const auto m = cuboid(2, 2, 2, 0.03, 0.03, 0.03);
  const auto sphere = icosphere(2, 10.0);  // mm
  std::ostringstream obj;
  obj.precision(17);
  for (const auto& v : sphere.vertices) obj << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& t : sphere.triangles) obj << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  auto open = sphere;
  open.triangles.pop_back();
  const std::map<std::string, std::string> files = {{"ascii.stl", ascii_stl(sphere)},
                                                    {"binary.stl", binary_stl(sphere)},
                                                    {"tool.obj", obj.str()},
                                                    {"open.stl", ascii_stl(open)},
                                                    {"garbage.stl", "not an stl file at all"},
                                                    {"tool.ply", "ply"}};
  for (const auto& [name, bytes] : files) dir.write(name, bytes);
  auto read = [&](const std::string& file) {
    nlohmann::json j = base_config(10, 0.0);
    j["boundary"]["tools"] = {{{"shape", "mesh"}, {"file", file}, {"scale", 0.001}, {"position", {0.015, 0.015, 0.05}}}};
    return hybrid::read_dhd_config(io::JsonReader(j, (dir.dir / "scene.json").string()), m);
  };
  for (const char* good : {"ascii.stl", "binary.stl", "tool.obj"}) {
    const auto c = read(good);
    const auto& s = *c.scene.tools.at(0).surface;
    EXPECT_EQ(s.num_triangles(), 320) << good;
    EXPECT_NEAR(s.upper().maxCoeff(), 0.01, 1e-12) << good;  // 10 mm
    Eigen::Vector3d n;
    EXPECT_LT(c.scene.tools[0].signed_distance(Eigen::Vector3d(0.015, 0.015, 0.045), Eigen::Vector3d(0.015, 0.015, 0.05), n), -0.004);
  }
  using test_support::input_error_of;
  for (const char* bad : {"open.stl", "garbage.stl", "tool.ply", "missing.stl"}) {
    const std::string e = input_error_of([&] { read(bad); });
    EXPECT_NE(e.find("scene.json: /boundary/tools/0/file"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  EXPECT_NE(input_error_of([&] { read("open.stl"); }).find("open.stl: expected a closed surface"), std::string::npos);

  // A fixed orientation: a 2 × 1 × 1 mm box turned 90° about z lies 1 mm along x and 2 mm along y.
  dir.write("long.stl", ascii_stl(box(Eigen::Vector3d(0, -0.5, -0.5), Eigen::Vector3d(2, 0.5, 0.5))));
  nlohmann::json j = base_config(10, 0.0);
  j["boundary"]["tools"] = {{{"shape", "mesh"}, {"file", "long.stl"}, {"scale", 0.001},
                             {"rotation", {{"axis", {0, 0, 1}}, {"degrees", 90}}}, {"position", {0.015, 0.015, 0.05}}}};
  const auto turned = hybrid::read_dhd_config(io::JsonReader(j, (dir.dir / "scene.json").string()), m);
  const auto& s = *turned.scene.tools.at(0).surface;
  EXPECT_NEAR(s.upper().y(), 0.002, 1e-15);
  EXPECT_NEAR(s.lower().x(), -0.0005, 1e-15);
  EXPECT_NEAR(s.upper().x(), 0.0005, 1e-15);
  j["boundary"]["tools"][0]["rotation"] = {{"axis", {0, 0, 0}}, {"degrees", 90}};
  EXPECT_NE(input_error_of([&] { hybrid::read_dhd_config(io::JsonReader(j, (dir.dir / "scene.json").string()), m); })
                .find("/boundary/tools/0/rotation/axis"),
            std::string::npos);
}

// dhd_sim with a bad tool file: exit code 2, one line naming the config and the member, no artifact.
TEST(MeshTool, DhdSimRefusesABadToolFileWithExitCode2) {
  const std::string exe = std::string(SOFTSIM_BIN_DIR) + "/dhd_sim";
  if (!fs::exists(exe)) GTEST_SKIP() << "dhd_sim is not built";
  Scratch dir("app");
  const auto m = cuboid(2, 2, 2, 0.03, 0.03, 0.03);
  io::Provenance prov;
  prov.tool = "test";
  io::write_artifact((dir.dir / "mesh.json").string(), io::kMeshSchema, io::kMeshSchemaVersion, prov, io::mesh_to_json(m));
  auto open = icosphere(1, 0.01);
  open.triangles.pop_back();
  dir.write("open.stl", ascii_stl(open));
  nlohmann::json j = base_config(10, 0.0);
  j["mesh"] = "mesh.json";
  j["boundary"]["tools"] = {{{"shape", "mesh"}, {"file", "open.stl"}, {"position", {0.015, 0.015, 0.05}}}};
  dir.write("bad.json", j.dump());
  const std::string out = (dir.dir / "out.json").string(), err = (dir.dir / "err.txt").string();
  const int status = std::system((exe + " --config " + (dir.dir / "bad.json").string() + " --out " + out + " 2> " + err).c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_FALSE(fs::exists(out));
  std::ifstream in(err);
  std::string first, second;
  std::getline(in, first);
  EXPECT_FALSE(std::getline(in, second)) << second;
  EXPECT_NE(first.find("/boundary/tools/0/file"), std::string::npos) << first;
  EXPECT_NE(first.find("open.stl: expected a closed surface"), std::string::npos) << first;
}

// The broad phase changes no result: with a small margin (many new grids and lists), three tools
// (a sphere with friction dragged over the face, a faceted sphere, a plane), and the haptic
// loop's jumps of set_tool_position, every displacement, force and energy equals the scan of
// every node bit for bit; and the search lists far fewer nodes than the surface has.
TEST(ContactSearch, BitIdenticalToTestingEveryNodeAndListsOnlyNodesNearTheTool) {
  const auto m = cuboid(12, 12, 4, 0.06, 0.06, 0.02);
  nlohmann::json j = base_config(1, 20.0);
  j["boundary"]["tools"] = {
      {{"shape", "sphere"}, {"radius", 0.008}, {"position", {0.02, 0.03, 0.028}}, {"friction", 0.4}, {"search_margin", 0.0007}},
      {{"shape", "capsule"}, {"radius", 0.004}, {"axis", {0.01, 0, 0}}, {"position", {0.045, 0.045, 0.0255}}},
      {{"shape", "plane"}, {"normal", {-1, 0, 0}}, {"position", {0.0605, 0, 0}}, {"travel", {-0.002, 0, 0}}, {"ramp_time", 0.1}}};
  auto c = parse(j, m);
  c.scene.tools[1].shape = dynamics::RigidTool::Shape::mesh;  // the capsule's place, a faceted sphere
  c.scene.tools[1].surface = std::make_shared<const mesh::ClosedSurface>(icosphere(3, 0.005), "sphere");
  auto all = c;
  all.explicit_solver.contact_search = false;
  hybrid::DhdScene grid(borrowed(m), c), scan(borrowed(m), all);
  int listed = 0;
  for (int frame = 0; frame < 150; ++frame) {
    const double s = frame / 150.0;
    const Eigen::Vector3d ball(0.02 + 0.02 * s, 0.03, 0.028 - 0.002 * std::min(1.0, 3 * s));
    // The probe jumps up out of the body for 10 frames in every 50, and back.
    const Eigen::Vector3d probe(0.045 - 0.01 * s, 0.045, 0.0255 - 0.0015 * s + (frame % 50 >= 30 && frame % 50 < 40 ? 0.02 : 0.0));
    for (hybrid::DhdScene* scene : {&grid, &scan}) {
      scene->solver().set_tool_position(0, ball);
      scene->solver().set_tool_position(1, probe);
      scene->step(4);
    }
    listed = std::max(listed, grid.solver().contact_search().listed(0));
    for (int q = 0; q < 3 * m.num_nodes(); ++q) ASSERT_EQ(grid.displacement()[q], scan.displacement()[q]) << frame << " " << q;
    for (int k = 0; k < 3; ++k) ASSERT_EQ(grid.solver().tool_force(k), scan.solver().tool_force(k)) << frame;
  }
  for (int k = 0; k < 3; ++k) EXPECT_GT(grid.solver().tool_contacts(k), 0) << k;
  EXPECT_EQ(grid.energies().back().external_work, scan.energies().back().external_work);
  const auto& search = grid.solver().contact_search();
  EXPECT_GT(search.rebuilds(0), 1);  // the pressed face moved more than half the margin
  EXPECT_GT(search.queries(0), search.rebuilds(0));  // the sphere moved on: new lists from the grid
  EXPECT_GT(search.queries(1), 2);                    // the probe's jumps
  const int free_surface = scan.solver().contact_search().listed(0);  // every free boundary node
  EXPECT_GT(free_surface, 300);
  EXPECT_LT(listed, free_surface / 4);
}
