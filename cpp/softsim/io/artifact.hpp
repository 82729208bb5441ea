#pragma once
// The artifact envelope shared by every executable:
//   { "schema": {"name": ..., "version": N},
//     "provenance": {"tool", "version", "git_commit", "config", "inputs": {path: sha256}, "seed"},
//     "payload": {...} }
// All quantities in payloads are SI (m, kg, s, N, Pa).
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "softsim/io/json_reader.hpp"

namespace softsim::io {

struct Provenance {
  std::string tool;
  nlohmann::json config = nlohmann::json::object();
  std::map<std::string, std::string> input_sha256;  // input path -> sha256 of its bytes
  std::optional<std::uint64_t> seed;
};

nlohmann::json make_artifact(const std::string& schema_name, int schema_version,
                             const Provenance& provenance, nlohmann::json payload);

// The envelope's "provenance" member: the tool, this build's version and commit, the config, inputs, seed.
nlohmann::json provenance_json(const Provenance& provenance);

// Builds the envelope and writes it atomically. Refuses to write a payload holding NaN or Inf
// (JSON cannot carry them and they always mean a numerical failure upstream).
void write_artifact(const std::string& path, const std::string& schema_name, int schema_version,
                    const Provenance& provenance, nlohmann::json payload);
// The same with the provenance already made (an artifact read back and written again keeps the
// provenance of the run that made it).
void write_artifact(const std::string& path, const std::string& schema_name, int schema_version,
                    const nlohmann::json& provenance, nlohmann::json payload);

// A parsed artifact. `payload()` is a strict reader over the payload.
class Artifact {
 public:
  // Reads and checks the envelope: schema name and version must match.
  static Artifact read(const std::string& path, const std::string& schema_name, int schema_version);
  const std::string& path() const { return path_; }
  const std::string& sha256() const { return sha256_; }
  JsonReader payload() const { return JsonReader(doc_->at("payload"), path_, "/payload"); }
  const nlohmann::json& document() const { return *doc_; }

 private:
  std::string path_;
  std::string sha256_;
  std::shared_ptr<nlohmann::json> doc_;
};

// Throws NumericalError naming the JSON pointer of the first non-finite number.
void require_finite(const nlohmann::json& value, const std::string& what);

}  // namespace softsim::io
