// Mesh invariants: conformity of the alternating 5-tet split, positive volumes summing to the
// box, a closed boundary of Euler characteristic 2, the paper's counts (000 §2.2.1, §3.1),
// and the importers on the real organ meshes shipped in experiments/data/meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "softsim/io/atomic_file.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/mesh_files.hpp"
#include "softsim/io/vtu_writer.hpp"
#include "softsim/meshing/gmsh_volume.hpp"
#include "softsim/mesh/cuboid.hpp"
#include "softsim/mesh/gmsh_reader.hpp"
#include "softsim/mesh/obj_reader.hpp"
#include "softsim/mesh/quality.hpp"
#include "softsim/mesh/surface.hpp"
#include "softsim/mesh/vtk_legacy_reader.hpp"
#include "softsim/mesh/vtu_reader.hpp"

#include "support/input_error.hpp"

using namespace softsim;

namespace {
mesh::TetMesh cuboid(int nx, int ny, int nz, Eigen::Vector3d size) {
  mesh::CuboidSpec s;
  s.cells = {nx, ny, nz};
  s.size = size;
  return mesh::make_cuboid(s);
}
const std::string kMeshDir = std::string(SOFTSIM_SOURCE_DIR) + "/experiments/data/meshes/";
const std::string kFixtureDir = std::string(SOFTSIM_SOURCE_DIR) + "/tests/data/meshes/";
using test_support::input_error_of;
}  // namespace

TEST(Cuboid, PaperCounts120NodesAnd300Tets) {
  const auto m = cuboid(3, 4, 5, {0.03, 0.04, 0.05});  // 4 x 5 x 6 nodes (000 Fig. 3)
  EXPECT_EQ(m.num_nodes(), 120);
  EXPECT_EQ(m.num_tets(), 300);
}

TEST(Cuboid, PaperCounts3564NodesAnd14450Tets) {
  const auto m = cuboid(17, 17, 10, {0.17, 0.17, 0.10});  // 000 §3.1, Table 1
  EXPECT_EQ(m.num_nodes(), 3564);
  EXPECT_EQ(m.num_tets(), 14450);
}

TEST(Cuboid, VolumesPositiveAndSumToBox) {
  const Eigen::Vector3d size(0.03, 0.02, 0.05);
  const auto m = cuboid(4, 3, 5, size);
  double total = 0;
  for (const auto& t : m.tets) {
    const double v = mesh::signed_volume(m, t);
    EXPECT_GT(v, 0);
    total += v;
  }
  EXPECT_NEAR(total, size.prod(), 1e-12 * size.prod());
}

TEST(Cuboid, ConformingFacesAndClosedSurface) {
  const auto m = cuboid(4, 3, 5, {1, 1, 1});
  const auto c = mesh::census(m);
  EXPECT_EQ(c.overshared_faces, 0);
  // Each cube face is split into 2 triangles: the box surface has 2 * 2 (nx ny + ny nz + nz nx).
  EXPECT_EQ(c.boundary_faces, 4 * (4 * 3 + 3 * 5 + 5 * 4));
  // Every face is used once (boundary) or twice (interior): 4 faces per tet in total.
  EXPECT_EQ(2 * c.interior_faces + c.boundary_faces, 4 * m.num_tets());
  EXPECT_EQ(c.euler_characteristic, 2);
  EXPECT_EQ(c.non_manifold_edges, 0);
  EXPECT_EQ(c.inward_triangles, 0);
  EXPECT_EQ(m.boundary.size(), static_cast<std::size_t>(c.boundary_faces));
}

TEST(Cuboid, SplitsAlternateSoThatOneSplitAloneWouldNotConform) {
  // With a single cell both splits are valid, and the two cells of a 2x1x1 box must use
  // different splits: the shared face then carries one diagonal, seen by both cells.
  const auto m = cuboid(2, 1, 1, {2, 1, 1});
  const auto c = mesh::census(m);
  EXPECT_EQ(c.overshared_faces, 0);
  EXPECT_EQ(c.boundary_faces, 4 * (2 * 1 + 1 * 1 + 1 * 2));
}

TEST(Cuboid, NodeSetsAndLayerTags) {
  const auto m = cuboid(3, 3, 4, {1, 1, 1});
  EXPECT_EQ(m.node_sets.at("bottom").size(), 16u);
  EXPECT_EQ(m.node_sets.at("top").size(), 16u);
  for (int v : m.node_sets.at("top")) EXPECT_DOUBLE_EQ(m.nodes[v].z(), 1.0);
  const auto& layer = m.element_tags.at("layer");
  ASSERT_EQ(layer.size(), m.tets.size());
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    double zc = 0;
    for (int v : m.tets[e]) zc += m.nodes[v].z() / 4;
    EXPECT_EQ(layer[e], static_cast<int>(std::floor(zc * 4)));
  }
}

TEST(Quality, RegularCubeSplitAngles) {
  const auto m = cuboid(1, 1, 1, {1, 1, 1});
  const auto q = mesh::quality_report(m);
  EXPECT_NEAR(q.total_volume, 1.0, 1e-14);
  EXPECT_NEAR(q.max_volume, 1.0 / 3.0, 1e-14);  // the central regular tet
  EXPECT_NEAR(q.min_volume, 1.0 / 6.0, 1e-14);  // the corner tets
  // Corner tets: 90° at the right-angle corner and acos(1/sqrt 3) = 54.7356° along the
  // slanted face; the central regular tet has acos(1/3) = 70.53°.
  EXPECT_NEAR(q.min_dihedral_deg, std::acos(1.0 / std::sqrt(3.0)) * 180.0 / M_PI, 1e-9);
  EXPECT_NEAR(q.max_dihedral_deg, 90.0, 1e-9);
  // The corner tet's smallest altitude is from its corner to the equilateral face: 1/sqrt(3).
  EXPECT_NEAR(q.min_altitude, 1.0 / std::sqrt(3.0), 1e-12);
  EXPECT_TRUE(q.slivers.empty());
}

TEST(Quality, FlattenedTetIsFlaggedAsSliver) {
  mesh::TetMesh m;
  m.nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 0.01}};
  m.tets = {{0, 1, 2, 3}};
  const auto q = mesh::quality_report(m, 5.0);
  EXPECT_EQ(q.slivers.size(), 1u);
}

TEST(GmshReader, Version22WithGapsAndPhysicalGroups) {
  const std::string text =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n10 0 0 0\n20 1 0 0\n30 0 1 0\n40 0 0 1\n50 1 1 1\n$EndNodes\n"
      "$Elements\n3\n1 2 2 7 1 10 20 30\n2 4 2 3 1 10 20 30 40\n3 4 2 5 1 20 30 40 50\n$EndElements\n";
  auto m = mesh::read_gmsh(text, "inline.msh");
  ASSERT_EQ(m.num_tets(), 2);
  EXPECT_EQ(m.num_nodes(), 5);
  EXPECT_EQ(m.element_tags.at("physical"), (std::vector<int>{3, 5}));
}

TEST(GmshReader, Version41WithEntities) {
  const std::string text =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
      "$Entities\n0 0 0 1\n7 0 0 0 1 1 1 1 42 0\n$EndEntities\n"
      "$Nodes\n1 4 1 9\n3 7 0 4\n1\n3\n5\n9\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n"
      "$Elements\n1 1 1 1\n3 7 4 1\n1 1 3 5 9\n$EndElements\n";
  auto m = mesh::read_gmsh(text, "inline41.msh");
  ASSERT_EQ(m.num_tets(), 1);
  EXPECT_EQ(m.element_tags.at("physical"), (std::vector<int>{42}));
}

TEST(GmshReader, RejectsGarbageWithFileAndLine) {
  try {
    mesh::read_gmsh("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 zero\n", "bad.msh");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.msh: line 6"), std::string::npos) << e.what();
  }
  EXPECT_THROW(mesh::read_gmsh("hello world", "notamesh.msh"), InputError);
}

TEST(VtkReader, ClassicLayout) {
  const std::string text =
      "# vtk DataFile Version 3.0\ntitle\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
      "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 2 1 3\nCELL_TYPES 1\n10\n"
      "CELL_DATA 1\nSCALARS materials int 1\nLOOKUP_TABLE default\n2\n";
  auto m = mesh::read_vtk_legacy(text, "inline.vtk");
  ASSERT_EQ(m.num_tets(), 1);
  EXPECT_EQ(m.element_tags.at("materials"), std::vector<int>{2});
}

TEST(ImportedMeshes, SofaLiverMsh1) {
  const auto m = io::load_mesh_file(kMeshDir + "sofa_liver.msh", {});
  EXPECT_EQ(m.num_nodes(), 181);
  EXPECT_EQ(m.num_tets(), 596);
  const auto c = mesh::census(m);
  EXPECT_EQ(c.overshared_faces, 0);
  EXPECT_EQ(c.euler_characteristic, 2);
  const auto q = mesh::quality_report(m);
  EXPECT_NEAR(q.total_volume, 36.56, 0.01);  // the data README's measured volume
}

TEST(ImportedMeshes, SofaLiver2SparseIds) {
  const auto m = io::load_mesh_file(kMeshDir + "sofa_liver2.msh", {});
  EXPECT_EQ(m.num_nodes(), 507);
  EXPECT_EQ(m.num_tets(), 1493);
  EXPECT_NEAR(mesh::quality_report(m).total_volume, 1.125, 0.001);
}

TEST(ImportedMeshes, ScaleConvertsUnits) {
  io::MeshFileOptions opt;
  opt.scale = 0.1;  // decimetres -> metres
  const auto m = io::load_mesh_file(kMeshDir + "sofa_liver2.msh", opt);
  EXPECT_NEAR(mesh::quality_report(m).total_volume, 1.125e-3, 1e-6);
}

TEST(VtkReader, Version51OffsetsConnectivityLayout) {
  // The layout of the breast mesh (VTK 5.1): OFFSETS/CONNECTIVITY instead of count prefixes.
  const std::string text =
      "# vtk DataFile Version 5.1\ntitle\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 float\n"
      "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\nCELLS 3 8\nOFFSETS vtktypeint64\n0 4 8\n"
      "CONNECTIVITY vtktypeint64\n0 1 2 3 1 2 3 4\nCELL_TYPES 2\n10\n10\n"
      "CELL_DATA 2\nSCALARS materials int 1\nLOOKUP_TABLE default\n1 3\n"
      "POINT_DATA 5\nSCALARS boundaryConditions int 1\nLOOKUP_TABLE default\n1 0 0 0 0\n";
  auto m = mesh::read_vtk_legacy(text, "inline51.vtk");
  ASSERT_EQ(m.num_tets(), 2);
  EXPECT_EQ(m.element_tags.at("materials"), (std::vector<int>{1, 3}));
}

TEST(VtkReader, FieldDataAsVtk9WritesItTagsIntegerCellArraysAndSkipsTheRest) {
  // Written by VTK 9.1 itself (tests/data/meshes/make_vtk_fixtures.py): the cell arrays are a
  // FIELD block (an int, a 64-bit int and a 6-component double array with METADATA), the point
  // data a VECTORS array, and one cell is a triangle.
  const std::string path = kFixtureDir + "vtk9_field.vtk";
  const auto m = mesh::read_vtk_legacy(io::read_text_file(path), path);
  ASSERT_EQ(m.num_tets(), 2);
  EXPECT_EQ(m.num_nodes(), 5);  // the triangle's own point is dropped
  EXPECT_EQ(m.tets[1], (mesh::Tet{1, 2, 3, 4}));
  EXPECT_EQ(m.element_tags.at("region"), (std::vector<int>{3, 5}));
  EXPECT_EQ(m.element_tags.at("material"), (std::vector<int>{1, 2}));
  EXPECT_EQ(m.element_tags.count("stress"), 0u);
}

TEST(VtkReader, FieldArraysMustMatchTheCellCount) {
  const std::string text =
      "# vtk DataFile Version 3.0\ntitle\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
      "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 2 1 3\nCELL_TYPES 1\n10\n"
      "CELL_DATA 1\nFIELD FieldData 1\nregion 1 2 int\n4 5\n";
  const std::string e = input_error_of([&] { mesh::read_vtk_legacy(text, "short.vtk"); });
  EXPECT_NE(e.find("short.vtk: line 13: expected 1 tuples"), std::string::npos) << e;
}

namespace {
// A mesh whose coordinates have no short decimal form (thirds, and a perturbation), with tags.
mesh::TetMesh awkward_mesh() {
  mesh::TetMesh m = cuboid(3, 2, 2, {0.1, 0.2 / 3.0, 1.0 / 7.0});
  for (int i = 0; i < m.num_nodes(); ++i) m.nodes[i] += 1e-3 * Eigen::Vector3d(std::sin(i), std::cos(3.0 * i), M_PI);
  m.element_tags["negative"] = std::vector<int>(m.num_tets(), -2147483647);
  return m;
}
bool same_bits(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::memcmp(a.data(), b.data(), 24) == 0; }
}  // namespace

TEST(VtuRoundTrip, EveryFormatReadsBackBitForBit) {
  const mesh::TetMesh m = awkward_mesh();
  io::VtuFields fields;
  fields.cell_ints = m.element_tags;
  fields.cell_scalars["skipped"] = std::vector<double>(m.num_tets(), 1.5);
  fields.point_vectors["displacement"] = m.nodes;
  const auto dir = std::filesystem::temp_directory_path();
  for (const auto format : {io::VtuFormat::ascii, io::VtuFormat::base64, io::VtuFormat::raw}) {
    const std::string path = (dir / (std::string("softsim_roundtrip_") + io::vtu_format_name(format) + ".vtu")).string();
    io::write_vtu(path, m, fields, format);
    const auto back = mesh::read_vtu(io::read_text_file(path), path);
    std::filesystem::remove(path);
    ASSERT_EQ(back.num_nodes(), m.num_nodes()) << io::vtu_format_name(format);
    for (int i = 0; i < m.num_nodes(); ++i)
      EXPECT_TRUE(same_bits(back.nodes[i], m.nodes[i])) << io::vtu_format_name(format) << " node " << i;
    EXPECT_EQ(back.tets, m.tets) << io::vtu_format_name(format);
    EXPECT_EQ(back.element_tags, m.element_tags) << io::vtu_format_name(format);
  }
}

TEST(VtuReader, ReadsUncompressedFilesWrittenByVtk) {
  // Inline base64 with UInt64 headers, and raw appended data with UInt32 headers, both with
  // VTK's <InformationKey> elements inside DataArrays and a triangle among the cells.
  for (const char* file : {"vtk9_base64.vtu", "vtk9_raw.vtu"}) {
    const std::string path = kFixtureDir + file;
    const auto m = mesh::read_vtu(io::read_text_file(path), path);
    ASSERT_EQ(m.num_tets(), 2) << file;
    EXPECT_EQ(m.num_nodes(), 5) << file;
    EXPECT_EQ(m.nodes[4], Eigen::Vector3d(1, 1, 1)) << file;
    EXPECT_EQ(m.tets[1], (mesh::Tet{1, 2, 3, 4})) << file;
    EXPECT_EQ(m.element_tags.at("region"), (std::vector<int>{3, 5})) << file;
    EXPECT_EQ(m.element_tags.at("material"), (std::vector<int>{1, 2})) << file;
  }
}

TEST(VtuReader, RefusesCompressedTruncatedAndMalformedFilesNamingThem) {
  const mesh::TetMesh m = cuboid(1, 1, 1, {1, 1, 1});
  const std::string path = (std::filesystem::temp_directory_path() / "softsim_bad.vtu").string();
  io::write_vtu(path, m, {}, io::VtuFormat::raw);
  const std::string raw = io::read_text_file(path);
  io::write_vtu(path, m, {}, io::VtuFormat::base64);
  const std::string b64 = io::read_text_file(path);
  std::filesystem::remove(path);
  const auto error = [](const std::string& text) { return input_error_of([&] { mesh::read_vtu(text, "bad.vtu"); }); };

  std::string compressed = b64;
  compressed.replace(compressed.find("header_type"), 0, "compressor=\"vtkZLibDataCompressor\" ");
  EXPECT_NE(error(compressed).find("bad.vtu: line 2: expected an uncompressed file"), std::string::npos)
      << error(compressed);
  const std::string cut = raw.substr(0, raw.size() - 40);  // the types block cut short
  EXPECT_NE(error(cut).find("in DataArray \"types\""), std::string::npos) << error(cut);
  io::write_vtu(path, m, {}, io::VtuFormat::ascii);
  const std::string ascii = io::read_text_file(path);
  std::filesystem::remove(path);
  const std::string cut_text = ascii.substr(0, ascii.find("<Points>") + 60);  // ends inside the points
  EXPECT_NE(error(cut_text).find("bad.vtu: line "), std::string::npos) << error(cut_text);
  std::string garbage = b64;
  garbage.replace(garbage.find("format=\"binary\">\n") + 17, 4, "!!!!");
  EXPECT_NE(error(garbage).find("base64"), std::string::npos) << error(garbage);
  EXPECT_NE(error("<VTKFile type=\"PolyData\">").find("expected type=\"UnstructuredGrid\""), std::string::npos);
  EXPECT_NE(error("not xml at all").find("bad.vtu"), std::string::npos);
}

TEST(GmshReader, BinaryFilesHoldTheSameMeshAsAscii) {
  // tests/data/meshes/two_boxes.geo meshed once by Gmsh and saved as ASCII and binary 4.1 and
  // 2.2: two physical volumes (7, 9) and a physical surface whose triangles are skipped.
  const auto read = [](const std::string& name) {
    const std::string path = kFixtureDir + name;
    return mesh::read_gmsh(io::read_text_file(path), path);
  };
  const mesh::TetMesh ascii = read("two_boxes_ascii41.msh");
  ASSERT_EQ(ascii.num_tets(), 200);
  const auto& physical = ascii.element_tags.at("physical");
  EXPECT_EQ(std::count(physical.begin(), physical.end(), 7) + std::count(physical.begin(), physical.end(), 9), 200);
  EXPECT_GT(std::count(physical.begin(), physical.end(), 7), 0);
  EXPECT_GT(std::count(physical.begin(), physical.end(), 9), 0);
  for (const char* name : {"two_boxes_bin41.msh", "two_boxes_ascii22.msh", "two_boxes_bin22.msh"}) {
    const mesh::TetMesh m = read(name);
    EXPECT_EQ(m.tets, ascii.tets) << name;
    EXPECT_EQ(m.element_tags, ascii.element_tags) << name;
    ASSERT_EQ(m.num_nodes(), ascii.num_nodes()) << name;
    // ASCII files hold 16 significant digits: one unit in the 16th digit of the unit boxes.
    for (int i = 0; i < m.num_nodes(); ++i) EXPECT_LE((m.nodes[i] - ascii.nodes[i]).norm(), 4e-16) << name << " node " << i;
  }
}

TEST(GmshReader, TruncatedBinaryFileNamesTheByte) {
  const std::string path = kFixtureDir + "two_boxes_bin41.msh";
  const std::string bytes = io::read_text_file(path);
  for (const std::size_t keep : {bytes.find("$Nodes") + 20, bytes.find("$Elements") + 100}) {
    const std::string e = input_error_of([&] { mesh::read_gmsh(bytes.substr(0, keep), "cut.msh"); });
    EXPECT_NE(e.find("cut.msh: byte "), std::string::npos) << e;
  }
  std::string swapped = bytes;  // the int 1 of another byte order
  const std::size_t one = swapped.find("4.1 1 8\n") + 8;
  std::swap(swapped[one], swapped[one + 3]);
  EXPECT_NE(input_error_of([&] { mesh::read_gmsh(swapped, "be.msh"); }).find("this machine's byte order"), std::string::npos);
}

namespace {
// A unit cube as an OBJ surface (quads, outward), and the same without its top face.
const std::string kCubeObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
const std::string kTopFace = "f 5 6 7 8\n";

std::string scratch_file(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  io::write_file_atomic(path, text);
  return path;
}
}  // namespace

TEST(ObjReader, FansPolygonsAndNamesTheLineOfABadIndex) {
  const auto s = mesh::read_obj(kCubeObj + kTopFace, "cube.obj");
  EXPECT_EQ(s.vertices.size(), 8u);
  EXPECT_EQ(s.triangles.size(), 12u);
  EXPECT_EQ(s.triangles[1], (mesh::Triangle{0, 2, 1}));
  const std::string e = input_error_of([] { mesh::read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "bad.obj"); });
  EXPECT_NE(e.find("bad.obj: line 4: expected a vertex index in range"), std::string::npos) << e;
}

TEST(SurfaceMeshing, ClosedCubeFillsItsVolumeAndAnOpenOneIsRefused) {
  // The remeshed surface of a polyhedron keeps its planar faces, so the tets fill exactly the
  // enclosed volume (1), all positively oriented after loading.
  const std::string cube = scratch_file("softsim_cube.obj", kCubeObj + kTopFace);
  io::MeshFileOptions opt;
  opt.surface_mesher = meshing::volume_from_surface;
  opt.target_edge = 0.4;
  const mesh::TetMesh m = io::load_mesh_file(cube, opt);
  const auto q = mesh::quality_report(m);
  EXPECT_NEAR(q.total_volume, 1.0, 1e-12);
  EXPECT_GT(q.min_volume, 0);
  EXPECT_EQ(mesh::census(m).euler_characteristic, 2);
  EXPECT_EQ(m.element_tags.at("region"), std::vector<int>(m.num_tets(), 1));

  const std::string open = scratch_file("softsim_open_cube.obj", kCubeObj);
  const std::string e = input_error_of([&] { io::load_mesh_file(open, opt); });
  EXPECT_NE(e.find(open + ": expected a closed triangle surface"), std::string::npos) << e;
  std::filesystem::remove(open);
  // Without a surface mesher (a tool that does not link libgmsh) the file is refused by name.
  opt.surface_mesher = nullptr;
  const std::string refused = input_error_of([&] { io::load_mesh_file(cube, opt); });
  EXPECT_NE(refused.find(cube + ": expected a volume mesh"), std::string::npos) << refused;
  std::filesystem::remove(cube);
}

namespace {
// The error a surface import ends in, as a ConfigInputError's pointer and message.
std::pair<std::string, std::string> config_error_of(const std::string& path, double target_edge) {
  try {
    meshing::volume_from_surface(path, target_edge);
  } catch (const ConfigInputError& e) {
    return {e.pointer, e.what()};
  }
  return {"", ""};
}

// Sets an environment variable for one scope.
struct ScopedEnv {
  ScopedEnv(const char* name, const char* value) : name_(name) { ::setenv(name, value, 1); }
  ~ScopedEnv() { ::unsetenv(name_); }
  const char* name_;
};
}  // namespace

TEST(SurfaceMeshing, GmshRunsUnderATimeLimitAndItsRefusalsKeepTheirMember) {
  // A refusal inside the meshing child (the target edge over the memory limit) keeps its member.
  const std::string cube = scratch_file("softsim_cube_fine.obj", kCubeObj + kTopFace);
  const auto [edge_pointer, edge_message] = config_error_of(cube, 1e-5);
  EXPECT_EQ(edge_pointer, "/source/target_edge");
  EXPECT_NE(edge_message.find("expected a size whose run fits the memory limit"), std::string::npos) << edge_message;
  std::filesystem::remove(cube);
  // A lone tetrahedron's four faces: Gmsh 4.8 never finishes filling it (mesher.md, known
  // limit). The child meshing it is ended at the limit, and the run refused naming it.
  const std::string tet = scratch_file("softsim_lone_tet.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                                               "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n");
  const ScopedEnv timeout("SOFTSIM_GMSH_TIMEOUT_S", "2");
  const auto [pointer, message] = config_error_of(tet, 0.0);
  std::filesystem::remove(tet);
  if (pointer.empty()) GTEST_SKIP() << "this Gmsh fills a lone tetrahedron: the hang the limit is for does not occur";
  EXPECT_EQ(pointer, "/source");
  EXPECT_NE(message.find("expected a surface Gmsh fills within 2 s (SOFTSIM_GMSH_TIMEOUT_S"), std::string::npos)
      << message;
}
