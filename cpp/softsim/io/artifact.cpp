#include "softsim/io/artifact.hpp"

#include <cmath>

#include "softsim/io/atomic_file.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/io/git_commit.hpp"
#include "softsim/io/sha256.hpp"
#include "softsim/version.hpp"

namespace softsim::io {

namespace {
bool find_non_finite(const nlohmann::json& v, std::string& where) {
  if (v.is_number_float()) return !std::isfinite(v.get<double>());
  if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (find_non_finite(v[i], where)) {
        where = "/" + std::to_string(i) + where;
        return true;
      }
  } else if (v.is_object()) {
    for (auto it = v.begin(); it != v.end(); ++it)
      if (find_non_finite(it.value(), where)) {
        where = "/" + it.key() + where;
        return true;
      }
  }
  return false;
}
}  // namespace

void require_finite(const nlohmann::json& value, const std::string& what) {
  std::string where;
  if (find_non_finite(value, where))
    throw NumericalError(what + ": non-finite value at " + (where.empty() ? "/" : where));
}

nlohmann::json provenance_json(const Provenance& provenance) {
  nlohmann::json inputs = nlohmann::json::object();
  for (const auto& [path, hash] : provenance.input_sha256) inputs[path] = hash;
  nlohmann::json prov = {{"tool", provenance.tool},
                         {"version", kVersion},
                         {"git_commit", git_commit()},
                         {"config", provenance.config},
                         {"inputs", inputs},
                         {"seed", nullptr}};
  if (provenance.seed) prov["seed"] = *provenance.seed;
  return prov;
}

namespace {
nlohmann::json envelope(const std::string& schema_name, int schema_version, nlohmann::json provenance,
                        nlohmann::json payload) {
  return {{"schema", {{"name", schema_name}, {"version", schema_version}}},
          {"provenance", std::move(provenance)},
          {"payload", std::move(payload)}};
}
}  // namespace

nlohmann::json make_artifact(const std::string& schema_name, int schema_version,
                             const Provenance& provenance, nlohmann::json payload) {
  return envelope(schema_name, schema_version, provenance_json(provenance), std::move(payload));
}

void write_artifact(const std::string& path, const std::string& schema_name, int schema_version,
                    const Provenance& provenance, nlohmann::json payload) {
  write_artifact(path, schema_name, schema_version, provenance_json(provenance), std::move(payload));
}

void write_artifact(const std::string& path, const std::string& schema_name, int schema_version,
                    const nlohmann::json& provenance, nlohmann::json payload) {
  require_finite(payload, schema_name + " payload");
  const nlohmann::json doc = envelope(schema_name, schema_version, provenance, std::move(payload));
  write_file_atomic(path, doc.dump(1) + "\n");
}

Artifact Artifact::read(const std::string& path, const std::string& schema_name,
                        int schema_version) {
  Artifact a;
  a.path_ = path;
  const std::string text = read_text_file(path);
  a.sha256_ = sha256_hex(text);
  a.doc_ = std::make_shared<nlohmann::json>(JsonReader::parse_text(text, path));
  const JsonReader root(*a.doc_, path);
  if (!a.doc_->is_object()) root.fail("an artifact object with schema, provenance and payload");
  const JsonReader schema = root.at("schema");
  const std::string name = schema.get_string("name");
  if (name != schema_name) schema.at("name").fail("schema \"" + schema_name + "\"");
  const auto version = schema.get_int("version");
  if (version != schema_version)
    schema.at("version").fail("schema version " + std::to_string(schema_version));
  root.at("provenance");
  root.at("payload");
  return a;
}

}  // namespace softsim::io
