#pragma once
// Reading the "rpim_dataset" artifact (schema version 1) written by rpim_precompute:
//   dataset {kind, count, seed}, loaded_node (1-based), top_nodes [[x, y, z]], cases
//   [{force, top_displacement}], unit_solutions [3 × [[ux, uy, uz]]], timing {...}.
// Only these members are read; the producer may carry more (plate, conditioning, ...).
#include <string>

#include "softsim/fit/dataset.hpp"
#include "softsim/io/json_reader.hpp"

namespace softsim::fit {

inline constexpr const char* kDatasetSchema = "rpim_dataset";
inline constexpr int kDatasetSchemaVersion = 1;
// Several datasets of one plate model built once ("members": {name: rpim_dataset payload}).
inline constexpr const char* kDatasetSetSchema = "rpim_dataset_set";
inline constexpr int kDatasetSetSchemaVersion = 1;

// A dataset named in a config: an rpim_dataset path (a string), or one member of an
// rpim_dataset_set ({"artifact": path, "member": name}; `member` empty for the former).
struct DatasetRef {
  std::string path;
  std::string member;
  std::string label() const { return member.empty() ? path : path + " [" + member + "]"; }
};
DatasetRef dataset_ref_from_json(const io::JsonReader& node);
// True for the object form (an object with "artifact"), which the string form is not.
bool is_dataset_member_ref(const io::JsonReader& node);

// Strict about what it reads: sizes, finiteness, loaded node in range, count == cases.
Dataset dataset_from_json(const io::JsonReader& payload, const std::string& source);

// Reads and checks the artifact at `path`.
Dataset read_dataset(const std::string& path);
// Reads and checks the dataset a reference names (the member of a set, or a whole artifact).
Dataset read_dataset(const DatasetRef& ref);

// nodes × 3 matrix from an array of [x, y, z] (expected_rows < 0: any count).
Eigen::MatrixXd read_xyz_rows(const io::JsonReader& array, long expected_rows = -1);

}  // namespace softsim::fit
