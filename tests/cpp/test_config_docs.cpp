// The config references of cpp/apps/*.md against the readers: every default a "key | ... |
// default | ..." table states as a JSON literal (a number, a quoted string, true/false, a list
// or an object) must be what the tool's reader gives when the key is left out, both with the
// whole block left out and with the block given empty (which runs the reader's fallbacks). The
// readers take their fallbacks from the config structs' member initialisers, so this checks the
// one place defaults live against the docs. Defaults written in words ("required", "—",
// "explicit", "5 (axis), 100 (random)") are not literals and are skipped; `{}` for a block
// stands for its members' defaults, which have rows of their own.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "softsim/fit/fit_config.hpp"
#include "softsim/fit/settings_json.hpp"
#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/meshless/organ_config.hpp"
#include "softsim/meshless/rpim_config.hpp"
#include "softsim/meshless/stiffness_solver.hpp"

#include "support/scenes.hpp"

using namespace softsim;
using nlohmann::json;

namespace {

struct DocDefault {
  std::string key;  // dotted path, e.g. "solver.steps"
  std::string text;  // the default cell as written
  json value;        // parsed, or discarded when the cell is not a JSON literal
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// The cells of a Markdown table row ("\|" is a pipe inside a cell).
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  for (std::size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
      cell += '|';
      ++i;
    } else if (line[i] == '|') {
      out.push_back(trim(cell));
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  return out;
}

std::string strip_backticks(std::string s) {
  s.erase(std::remove(s.begin(), s.end(), '`'), s.end());
  return trim(s);
}

json parse_literal(const std::string& text) { return json::parse(strip_backticks(text), nullptr, false); }

// Every row of a table with a "key" and a "default" column. A section headed by a backticked
// name ("### `solver`") prefixes its keys ("solver.steps"). A row naming several keys
// ("`a`, `b`") with as many comma-separated defaults gives one entry each.
std::vector<DocDefault> doc_defaults(const std::string& md_file) {
  std::ifstream in(std::string(SOFTSIM_SOURCE_DIR) + "/cpp/apps/" + md_file);
  EXPECT_TRUE(in) << md_file;
  // "### `plate` (modes ...)" prefixes; "### `penalty`, `solver`" and "### Mode `dataset`" do not.
  static const std::regex kSection(R"(^#+ `([a-z_]+)`(?!,).*$)");
  static const std::regex kName("`([A-Za-z_][A-Za-z0-9_.]*)`");
  std::vector<DocDefault> out;
  std::string line, prefix;
  int key_col = -1, default_col = -1;
  while (std::getline(in, line)) {
    std::smatch m;
    if (!line.empty() && line[0] == '#') {
      prefix = std::regex_match(line, m, kSection) ? m[1].str() : "";
      continue;
    }
    if (line.empty() || line[0] != '|') {
      key_col = default_col = -1;
      continue;
    }
    const std::vector<std::string> c = cells(line);
    if (key_col < 0) {  // a header row
      for (std::size_t i = 0; i < c.size(); ++i) {
        if (c[i] == "key") key_col = static_cast<int>(i);
        if (c[i] == "default") default_col = static_cast<int>(i);
      }
      if (default_col < 0) key_col = -2;  // a table without defaults: skip to its end
      continue;
    }
    if (key_col == -2 || default_col < 0 || c.size() <= static_cast<std::size_t>(std::max(key_col, default_col)) ||
        c[key_col].rfind("---", 0) == 0)
      continue;
    std::vector<std::string> names;
    const std::string& kc = c[key_col];
    for (auto it = std::sregex_iterator(kc.begin(), kc.end(), kName); it != std::sregex_iterator(); ++it)
      names.push_back((*it)[1].str());
    if (names.empty()) continue;
    std::vector<std::string> texts = {c[default_col]};
    if (names.size() > 1) {
      texts.clear();
      std::stringstream ss(strip_backticks(c[default_col]));
      for (std::string t; std::getline(ss, t, ',');) texts.push_back(trim(t));
      if (texts.size() != names.size()) continue;  // not one default per key: a sentence
    }
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::string key =
          prefix.empty() || names[i].rfind(prefix + ".", 0) == 0 ? names[i] : prefix + "." + names[i];
      out.push_back({key, texts[i], parse_literal(texts[i])});
    }
  }
  return out;
}

// Checks every literal default of `md_file` against `resolved` (the reader's result as nested
// JSON); returns how many were checked.
int check_defaults(const std::string& md_file, const json& resolved, const std::string& config_label) {
  int checked = 0;
  for (const DocDefault& d : doc_defaults(md_file)) {
    if (d.value.is_discarded()) continue;
    json::json_pointer ptr("/" + std::regex_replace(d.key, std::regex("\\."), "/"));
    if (!resolved.contains(ptr)) {
      ADD_FAILURE() << md_file << ": `" << d.key << "` documents the default " << d.text
                    << " but the test does not know the reader's value (" << config_label << ")";
      continue;
    }
    const json& got = resolved.at(ptr);
    ++checked;
    if (d.value == json::object() && got.is_object()) continue;  // a block: its members have rows
    // Numbers compare by value (5000 documents the double 5000.0).
    const bool same = d.value.is_number() && got.is_number() ? d.value.get<double>() == got.get<double>()
                                                             : d.value == got;
    EXPECT_TRUE(same) << md_file << ": `" << d.key << "` is documented as " << d.text << " but the reader gives "
                      << got.dump() << " (" << config_label << ")";
  }
  return checked;
}

json vec3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// ---- dhd_sim ----

json resolved(const hybrid::DhdConfig& c) {
  const auto& e = c.explicit_solver;
  const auto& st = c.static_options;
  const auto& o = c.output;
  return {{"material",
           {{"model", c.model},
            {"E", c.material.elastic.youngs_modulus},
            {"nu", c.material.elastic.poisson_ratio},
            {"density", c.material.elastic.density},
            // Read only with "transversely_isotropic": the default is the law's member initialiser.
            {"fibre", vec3(material::TransverselyIsotropic{}.fibre)}}},
          {"damping", {{"alpha", c.damping_alpha}}},
          {"threads", c.threads},
          {"cuts", json::array_t(c.cuts.size())},
          {"solver",
           {{"kind", c.static_solver ? "static" : "explicit"},
            {"steps", e.steps},
            {"safety_factor", e.safety_factor},
            {"force_dt", e.force_dt},
            {"dt_check_interval", e.dt_check_interval},
            {"critical_step", hybrid::critical_step_name(e.critical_step)},
            {"energy_interval", e.energy_interval},
            {"energy_growth_limit", e.energy_growth_limit},
            {"contact_search", e.contact_search ? "grid" : "all"},
            {"linear_precision", fem::linear_precision_name(e.linear_precision)},
            {"increments", st.increments},
            {"max_iterations", st.max_iterations},
            {"tolerance", st.tolerance}}},
          {"output",
           {{"vtu_interval", o.vtu_interval},
            {"vtu_format", io::vtu_format_name(o.vtu_format)},
            {"trajectories", o.trajectory_nodes},
            {"trajectory_interval", o.trajectory_interval},
            {"velocity", o.velocity},
            {"displacement", o.displacement}}}};
}

// ---- marquardt_fit ----

json resolved(const fit::FitConfig& c) {
  json r = fit::fit_settings_to_json(c.settings);
  r["validation"] = json::array_t(c.validation.size());
  r["check_forces"] = c.check_forces;
  r["examples"] = c.examples;
  r["timing"] = {{"evaluations", c.evaluations}};
  return r;
}

// ---- rpim_precompute ----

json length(const meshless::LengthSpec& l) {
  return l.kind == meshless::LengthSpec::Kind::absolute ? json{{"length", l.value}} : json{{"spacing_factor", l.value}};
}

json resolved(const meshless::PlateScene& plate, const meshless::RpimSettings& s, const meshless::DatasetSpec& random,
              const meshless::DatasetSpec& check, const meshless::DatasetOutput& out, const meshless::BlockStudy& b,
              const meshless::OrganScene& organ) {
  json support = s.support == meshless::SupportRule::Kind::radius ? length(s.support_radius)
                                                                  : json{{"count", s.support_count}};
  support["kind"] = s.support == meshless::SupportRule::Kind::radius ? "radius" : "nearest";
  return {{"plate", meshless::plate_scene_json(plate)},
          {"rpim",
           {{"alpha_c", s.alpha_c},
            {"q", s.q},
            {"d_c", length(s.d_c)},
            {"polynomial", s.polynomial == meshless::PolynomialBasis::linear ? "linear" : "none"},
            {"support", support},
            {"max_moment_condition", s.max_moment_condition},
            {"max_partition_error", s.max_partition_error}}},
          {"penalty",
           {{"kind", s.penalty.kind == meshless::PenaltyParams::Kind::scale_block ? "scale_block" : "add_diagonal"},
            {"lambda", s.penalty.lambda}}},
          {"solver", meshless::solver_name(s.solver)},
          {"dataset", {{"max_force", random.max_force}, {"seed", random.seed}, {"force", vec3(check.force)}}},
          {"output", {{"all_nodes", out.all_nodes}, {"stiffness_conditioning", out.stiffness_conditioning}}},
          {"block",
           {{"field", b.field == meshless::ManufacturedField::plane_wave ? "plane_wave" : "linear_patch"},
            {"edge", b.edge},
            {"youngs_modulus", b.youngs_modulus},
            {"poisson_ratio", b.poisson_ratio},
            {"gauss_order", b.gauss_order}}},
          {"organ",
           {{"fixed_sets", organ.fixed_sets},
            {"loaded_set", organ.loaded_set},
            {"youngs_modulus", organ.youngs_modulus},
            {"poisson_ratio", organ.poisson_ratio},
            {"tet_rule", organ.tet_rule},
            {"body_force", vec3(organ.body_force)}}}};
}

std::optional<io::JsonReader> block(const json& doc, const char* key) {
  if (!doc.contains(key)) return std::nullopt;
  return io::JsonReader(doc, "config.json").at(key);
}

}  // namespace

TEST(ConfigDocs, TheParserFindsTheDocumentedDefaults) {
  // The parser itself: known rows of each file come out with their keys and values.
  auto find = [](const std::vector<DocDefault>& rows, const std::string& key) -> json {
    for (const auto& r : rows)
      if (r.key == key) return r.value;
    return "not found";
  };
  const auto dhd = doc_defaults("dhd_sim.md");
  EXPECT_EQ(find(dhd, "solver.steps"), 1000);
  EXPECT_EQ(find(dhd, "material.model"), "neo_hookean_paper");
  EXPECT_EQ(find(dhd, "damping"), json({{"alpha", 0}}));
  const auto rpim = doc_defaults("rpim_precompute.md");
  EXPECT_EQ(find(rpim, "plate.nodes"), json({11, 11, 3}));
  EXPECT_EQ(find(rpim, "block.poisson_ratio"), 0.3);
  EXPECT_TRUE(find(rpim, "dataset.count").is_discarded());  // "5 (axis), 100 (random)"
  const auto fit = doc_defaults("marquardt_fit.md");
  EXPECT_EQ(find(fit, "cv.max_orders.surface"), json({8, 8}));
}

TEST(ConfigDocs, DhdSimDefaultsAreTheReadersDefaults) {
  const mesh::TetMesh mesh = test_scenes::cuboid(2, 2, 2, 0.02, 0.02, 0.02);
  const json absent = {{"mesh", "mesh.json"}};
  const json empty = {{"mesh", "mesh.json"}, {"material", json::object()}, {"damping", json::object()},
                      {"partition", json::object()}, {"solver", json::object()}, {"output", json::object()},
                      {"bench", json::object()}};
  for (const auto& [label, doc] : {std::pair{"blocks left out", absent}, std::pair{"empty blocks", empty}}) {
    const hybrid::DhdConfig c = hybrid::read_dhd_config(io::JsonReader(doc, "config.json"), mesh);
    EXPECT_GE(check_defaults("dhd_sim.md", resolved(c), label), 20) << label;
  }
}

TEST(ConfigDocs, MarquardtFitDefaultsAreTheReadersDefaults) {
  const json absent = {{"datasets", {{"z", "axis_z.json"}}}};
  const json empty = {{"datasets", {{"z", "axis_z.json"}}},
                      {"cv", {{"max_orders", json::object()}}},
                      {"solver", json::object()},
                      {"orders", json::object()},
                      {"timing", json::object()}};
  for (const auto& [label, doc] : {std::pair{"blocks left out", absent}, std::pair{"empty blocks", empty}}) {
    const fit::FitConfig c = fit::read_fit_config(io::JsonReader(doc, "config.json"), false);
    EXPECT_GE(check_defaults("marquardt_fit.md", resolved(c), label), 20) << label;
  }
}

TEST(ConfigDocs, RpimPrecomputeDefaultsAreTheReadersDefaults) {
  const json absent = json::object();
  const json empty = {{"plate", json::object()}, {"rpim", json::object()}, {"penalty", json::object()},
                      {"output", json::object()}, {"block", json::object()}};
  for (const auto& [label, doc] : {std::pair{"blocks left out", absent}, std::pair{"empty blocks", empty}}) {
    const json random = {{"kind", "random"}}, check = {{"kind", "check"}};
    const auto plate = meshless::read_plate_scene(block(doc, "plate"));
    const auto settings = meshless::read_rpim_settings(block(doc, "rpim"), block(doc, "penalty"), block(doc, "solver"));
    const auto r = meshless::read_dataset_spec(io::JsonReader(random, "config.json"));
    const auto k = meshless::read_dataset_spec(io::JsonReader(check, "config.json"));
    const auto out = meshless::read_dataset_output(block(doc, "output"));
    const auto b = meshless::read_block_study(block(doc, "block"));
    // The organ block needs its mesh (an input file that must exist); nothing else.
    const std::string mesh = (std::filesystem::temp_directory_path() / "config_docs_organ_mesh.json").string();
    std::ofstream(mesh) << "{}";
    const json organ_doc = {{"organ", {{"mesh", mesh}}}};
    const auto organ = meshless::read_organ_scene(io::JsonReader(organ_doc, "config.json").at("organ"));
    std::filesystem::remove(mesh);
    EXPECT_GE(check_defaults("rpim_precompute.md", resolved(plate, settings, r, k, out, b, organ), label), 20) << label;
  }
}
