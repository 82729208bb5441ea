// The artifact envelope and strict reading: every complaint names the file and JSON pointer.
// The provenance commit is the source tree's, flagged dirty, whatever the current directory.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "softsim/io/artifact.hpp"
#include "softsim/io/base64.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/git_commit.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/io/mesh_artifact.hpp"
#include "softsim/io/result_fields.hpp"
#include "softsim/io/sha256.hpp"
#include "softsim/io/utf8.hpp"

#include "support/input_error.hpp"

using namespace softsim;

TEST(Sha256, KnownVectors) {
  EXPECT_EQ(io::sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(io::sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(io::sha256_hex(std::string(1000, 'a')),
            "41edece42d63e8d9bf515a9ba6932e1c20cbc9f5a5d134645adb5db1b9737ea3");
}

TEST(Base64, Rfc4648VectorsAndRoundTrip) {
  const std::pair<std::string, std::string> vectors[] = {{"", ""},          {"f", "Zg=="},        {"fo", "Zm8="},
                                                         {"foo", "Zm9v"},   {"foob", "Zm9vYg=="}, {"fooba", "Zm9vYmE="},
                                                         {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : vectors) {
    EXPECT_EQ(io::base64_encode(plain), encoded);
    EXPECT_EQ(io::base64_decode(encoded), plain);
  }
  std::string bytes;
  for (int i = 0; i < 256; ++i) bytes.push_back(static_cast<char>(i));
  EXPECT_EQ(io::base64_decode(io::base64_encode(bytes)), bytes);
}

TEST(Base64, DecodesSeparatelyPaddedStreamsAndRefusesGarbage) {
  // VTK's header-then-data layout when the two are encoded apart; whitespace is skipped.
  EXPECT_EQ(io::base64_decode("Zg==\n  Zm9v Yg=="), std::string("ffoob"));
  EXPECT_EQ(io::base64_decode("Zm9"), std::nullopt);     // a group cut short
  EXPECT_EQ(io::base64_decode("Zm9v!A=="), std::nullopt); // not the alphabet
  EXPECT_EQ(io::base64_decode("Z==="), std::nullopt);     // padding cannot fill three places
  EXPECT_EQ(io::base64_decode("Zg=a"), std::nullopt);     // data after padding within a group
}

using test_support::input_error_of;

TEST(JsonReader, MissingFieldNamesPointer) {
  const nlohmann::json j = {{"a", {{"b", 1}}}};
  io::JsonReader r(j, "cfg.json");
  EXPECT_EQ(input_error_of([&] { r.at("a").at("c"); }), "cfg.json: /a/c: missing required field");
}

TEST(JsonReader, WrongTypeNamesExpectation) {
  const nlohmann::json j = {{"E", "soft"}};
  io::JsonReader r(j, "cfg.json");
  EXPECT_EQ(input_error_of([&] { r.get_double("E"); }),
            "cfg.json: /E: expected a number, got string \"soft\"");
}

TEST(JsonReader, UnknownFieldRejected) {
  const nlohmann::json j = {{"E", 1.0}, {"nu_typo", 0.3}};
  io::JsonReader r(j, "cfg.json");
  r.get_double("E");
  EXPECT_EQ(input_error_of([&] { r.reject_unknown(); }), "cfg.json: /nu_typo: unknown field");
}

TEST(JsonReader, ObjectWithOnlyOptionalMembersRefusesAnotherType) {
  // {"solver": "implicit"}: every optional member reads as absent, so only the final check can
  // tell that the value is not an object.
  const nlohmann::json j = {{"solver", "implicit"}};
  const io::JsonReader solver = io::JsonReader(j, "cfg.json").at("solver");
  EXPECT_EQ(solver.get_string("kind", "implicit"), "implicit");
  EXPECT_NE(input_error_of([&] { solver.reject_unknown(); }).find("cfg.json: /solver: expected an object"),
            std::string::npos);
}

TEST(JsonReader, PositiveAndChoiceChecks) {
  const nlohmann::json j = {{"E", -3.0}, {"kind", "cube"}, {"n", 2.5}};
  io::JsonReader r(j, "c.json");
  EXPECT_NE(input_error_of([&] { r.get_positive("E"); }).find("/E: expected a positive number"), std::string::npos);
  EXPECT_NE(input_error_of([&] { r.get_choice("kind", {"cuboid", "file"}); }).find("one of \"cuboid\", \"file\""),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { r.get_int("n"); }).find("expected an integer"), std::string::npos);
}

TEST(JsonReader, TruncatedFileIsInputError) {
  const auto path = std::filesystem::temp_directory_path() / "softsim_truncated.json";
  std::ofstream(path) << "{\"a\": [1, 2";
  EXPECT_NE(input_error_of([&] { io::JsonReader::parse_file(path.string()); }).find("invalid JSON"), std::string::npos);
  std::ofstream(path) << "{\"a\": NaN}";
  EXPECT_NE(input_error_of([&] { io::JsonReader::parse_file(path.string()); }).find("invalid JSON"), std::string::npos);
  std::filesystem::remove(path);
}

TEST(Artifact, RoundTripAndSchemaCheck) {
  const auto path = (std::filesystem::temp_directory_path() / "softsim_artifact.json").string();
  io::Provenance p;
  p.tool = "test";
  p.seed = 7;
  io::write_artifact(path, "thing", 2, p, {{"x", 1.5}});
  const auto a = io::Artifact::read(path, "thing", 2);
  EXPECT_DOUBLE_EQ(a.payload().get_double("x"), 1.5);
  EXPECT_EQ(a.document()["provenance"]["seed"], 7);
  EXPECT_EQ(a.sha256(), io::sha256_file(path));
  EXPECT_THROW(io::Artifact::read(path, "other", 2), InputError);
  EXPECT_THROW(io::Artifact::read(path, "thing", 1), InputError);
  std::filesystem::remove(path);
}

TEST(ResultFields, NodalDisplacementsReadBackAndMalformedFieldsNamePointerAndMesh) {
  const auto path = (std::filesystem::temp_directory_path() / "softsim_result_fields.json").string();
  const auto result = [&](const nlohmann::json& displacement) {
    io::write_artifact(path, "dhd_result", 1, io::Provenance{}, {{"displacement", displacement}});
    return io::Artifact::read(path, "dhd_result", 1);
  };
  EXPECT_EQ(io::read_nodal_displacements(result({{1, 2, 3}, {4, 5, 6}}), 2), (std::vector<double>{1, 2, 3, 4, 5, 6}));
  const auto message = [&](const nlohmann::json& displacement, int nodes, const std::string& mesh) {
    try {
      io::read_nodal_displacements(result(displacement), nodes, mesh);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string wrong_count = message({{1, 2, 3}}, 2, "mesh.json");
  EXPECT_NE(wrong_count.find("/payload/displacement"), std::string::npos) << wrong_count;
  EXPECT_NE(wrong_count.find("one displacement per mesh node (2) of mesh.json"), std::string::npos) << wrong_count;
  for (const nlohmann::json& bad_row : {nlohmann::json{1, 2}, nlohmann::json(7.0)}) {
    const std::string m = message({{1, 2, 3}, bad_row}, 2, "");
    EXPECT_NE(m.find("/payload/displacement/1"), std::string::npos) << m;
    EXPECT_NE(m.find("[ux, uy, uz]"), std::string::npos) << m;
  }
  std::filesystem::remove(path);
}

TEST(Artifact, NonFinitePayloadIsNumericalFailureAndNothingIsWritten) {
  const auto path = (std::filesystem::temp_directory_path() / "softsim_nan.json").string();
  std::filesystem::remove(path);
  io::Provenance p;
  EXPECT_THROW(io::write_artifact(path, "thing", 1, p, {{"u", {1.0, std::nan("")}}}), NumericalError);
  EXPECT_FALSE(std::filesystem::exists(path));
}

namespace {
nlohmann::json unit_tet_payload() {
  return {{"units", "m"},
          {"nodes", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
          {"tets", {{0, 1, 2, 3}}},
          {"boundary", nlohmann::json::array()},
          {"node_sets", {{"top", {3}}}},
          {"element_tags", {{"layer", {0}}}}};
}
std::string mesh_error(const nlohmann::json& payload) {
  return input_error_of([&] { io::mesh_from_json(io::JsonReader(payload, "m.json", "/payload")); });
}
}  // namespace

TEST(MeshArtifact, ValidPayloadReads) {
  const auto m = io::mesh_from_json(io::JsonReader(unit_tet_payload(), "m.json", "/payload"));
  EXPECT_EQ(m.num_tets(), 1);
  EXPECT_EQ(m.node_sets.at("top"), std::vector<int>{3});
}

TEST(MeshArtifact, NegativeVolumeNamesElement) {
  auto p = unit_tet_payload();
  p["tets"][0] = {0, 2, 1, 3};
  EXPECT_NE(mesh_error(p).find("m.json: /payload/tets/0: expected a positively oriented tetrahedron"),
            std::string::npos);
}

TEST(MeshArtifact, IndexOutOfRangeAndDuplicates) {
  auto p = unit_tet_payload();
  p["tets"][0] = {0, 1, 2, 7};
  EXPECT_NE(mesh_error(p).find("/payload/tets/0/3: expected a node index in [0, 3]"), std::string::npos);
  p = unit_tet_payload();
  p["tets"][0] = {0, 1, 1, 3};
  EXPECT_NE(mesh_error(p).find("4 distinct node indices"), std::string::npos);
  p = unit_tet_payload();
  p["node_sets"]["top"] = {-1};
  EXPECT_NE(mesh_error(p).find("/payload/node_sets/top/0"), std::string::npos);
}

TEST(MeshArtifact, TagSizeUnitsAndUnknownField) {
  auto p = unit_tet_payload();
  p["element_tags"]["layer"] = {0, 1};
  EXPECT_NE(mesh_error(p).find("one tag per tetrahedron"), std::string::npos);
  p = unit_tet_payload();
  p["units"] = "mm";
  EXPECT_NE(mesh_error(p).find("/payload/units"), std::string::npos);
  p = unit_tet_payload();
  p["colour"] = "red";
  EXPECT_NE(mesh_error(p).find("/payload/colour: unknown field"), std::string::npos);
}

namespace {
// Standard output of a shell command without its final newline; "unknown" if it fails (the
// library's convention for a commit it cannot read).
std::string output_of(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen((command + " 2>/dev/null").c_str(), "r");
  if (!pipe) return "unknown";
  char buffer[256];
  while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
  if (::pclose(pipe) != 0) return "unknown";
  if (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}
}  // namespace

TEST(GitCommit, IsTheSourceTreesWhateverTheCurrentDirectory) {
  if (std::getenv("SOFTSIM_GIT_COMMIT")) GTEST_SKIP() << "SOFTSIM_GIT_COMMIT replaces the source tree's commit";
  const std::string expected = output_of("git -C '" SOFTSIM_SOURCE_DIR "' describe --always --dirty");
  // Run from a directory outside any repository (the old reading, of the current directory,
  // gave "unknown" there and another repository's commit elsewhere).
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(std::filesystem::temp_directory_path());
  const std::string reported = io::git_commit();
  std::filesystem::current_path(cwd);
  EXPECT_EQ(reported, expected);
}

TEST(GitCommit, FlagsADirtyTreeAndFallsBackToUnknown) {
  // A quote and a space in the path: it must reach git as one argument.
  const auto repo = std::filesystem::temp_directory_path() / ("softsim git's " + std::to_string(::getpid()));
  std::filesystem::remove_all(repo);
  std::filesystem::create_directories(repo);
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(repo);
  std::ofstream("tracked.txt") << "1\n";
  const std::string committed = output_of(
      "git init -q && git add tracked.txt && "
      "git -c user.name=softsim -c user.email=softsim@localhost -c commit.gpgsign=false commit -q -m one && "
      "git rev-parse --short HEAD");
  std::filesystem::current_path(cwd);
  ASSERT_NE(committed, "unknown") << "could not make a repository with git in " << repo;

  EXPECT_EQ(io::describe_commit(repo.string()), committed);
  std::ofstream(repo / "tracked.txt") << "2\n";
  EXPECT_EQ(io::describe_commit(repo.string()), committed + "-dirty");
  // The source tree gone (an installed binary on another machine): no commit, and no error.
  std::filesystem::remove_all(repo);
  EXPECT_EQ(io::describe_commit(repo.string()), "unknown");
}

TEST(Utf8, WellFormedTextPassesAndTheFirstBadByteIsFound) {
  // What nlohmann::json will write (RFC 3629) is exactly what passes: every text it accepts
  // here dumps, every text refused here would make the dump throw.
  for (const std::string ok : {"", "region", "Gewebe \xC3\xA4", "\xE2\x82\xAC", "\xF0\x9F\x98\x80", "\xEF\xBF\xBF"}) {
    EXPECT_EQ(io::first_invalid_utf8(ok), std::string::npos) << ok;
    EXPECT_NO_THROW(nlohmann::json({{ok, 1}}).dump());
  }
  const std::pair<std::string, std::size_t> bad[] = {
      {"r\xFF", 1},            // never a UTF-8 byte
      {"ab\xC3", 2},           // a sequence cut short
      {"\xC0\xAF", 0},         // overlong "/"
      {"x\xED\xA0\x80", 1},    // a UTF-16 surrogate
      {"\xF4\x90\x80\x80", 0}, // above U+10FFFF
      {"\x80", 0}};            // a continuation byte alone
  for (const auto& [text, at] : bad) {
    EXPECT_EQ(io::first_invalid_utf8(text), at);
    EXPECT_THROW(nlohmann::json({{text, 1}}).dump(), nlohmann::json::type_error);
  }
}
