#pragma once
// The marquardt_fit configuration of modes `fit` and `cv` (documented in
// cpp/apps/marquardt_fit.md), read strictly from JSON: the fitting settings (settings_json.hpp),
// the datasets along each axis, and, in mode `fit` only, the validation datasets, the check
// forces, the stored examples and the timing. Any problem is an InputError naming the file and
// JSON pointer. Defaults are the member initialisers below (one place; the reader falls back
// to them).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "softsim/fit/dataset_json.hpp"
#include "softsim/fit/fit_driver.hpp"
#include "softsim/fit/static_series.hpp"
#include "softsim/io/json_reader.hpp"

namespace softsim::fit {

struct FitConfig {
  FitSettings settings;
  // Per axis (x, y, z): an rpim_dataset path or a member of an rpim_dataset_set (`datasets`;
  // empty path: no dataset along that axis), or a series of static solutions (static_series.hpp),
  // whose `datasets` entry holds the series' mesh path.
  std::array<DatasetRef, 3> datasets;
  std::array<std::optional<StaticSeries>, 3> series;
  // Mode `fit` only.
  std::vector<DatasetRef> validation;
  std::vector<double> check_forces = {0.2, 0.4, 0.6, 0.8, 1.0};  // N, 002 §5.1.1
  int examples = 3;                                             // validation cases stored in full
  std::int64_t evaluations = 100000;                            // timed playbacks; 0: no timing
};

// Reads the whole config (`cv_mode`: mode `cv`, which has no validation, checks, examples or
// timing) and rejects unknown keys.
FitConfig read_fit_config(const io::JsonReader& config, bool cv_mode);

}  // namespace softsim::fit
