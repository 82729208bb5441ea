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

// Strict about what it reads: sizes, finiteness, loaded node in range, count == cases.
Dataset dataset_from_json(const io::JsonReader& payload, const std::string& source);

// Reads and checks the artifact at `path`.
Dataset read_dataset(const std::string& path);

// nodes × 3 matrix from an array of [x, y, z] (expected_rows < 0: any count).
Eigen::MatrixXd read_xyz_rows(const io::JsonReader& array, long expected_rows = -1);

}  // namespace softsim::fit
