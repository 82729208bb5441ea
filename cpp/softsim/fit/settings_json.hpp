#pragma once
// The fitting settings of a marquardt_fit config (see cpp/apps/marquardt_fit.md):
//   "basis", "input_scaling", "surface_model", "cv" {...}, "solver" {...}, "orders" {...}.
// Reads these members of `config` (marking them known); the caller reads the rest and calls
// reject_unknown(). A member left out keeps FitSettings' default (its member initialisers, the
// one place defaults are set).
#include <nlohmann/json.hpp>

#include "softsim/fit/fit_driver.hpp"
#include "softsim/io/json_reader.hpp"

namespace softsim::fit {

FitSettings fit_settings_from_json(const io::JsonReader& config);

// The settings as written back into an artifact (what was actually used, defaults included).
nlohmann::json fit_settings_to_json(const FitSettings& settings);

// {"model": "separable", "orders": [a, b]} | {"model": "bivariate", "degree": n} |
// {"model": "trivariate", "degree": n, "z_degree": m (optional, default n)} | {"model": "zero"}
SurfaceTerms surface_terms_from_json(const io::JsonReader& node);
nlohmann::json surface_terms_to_json(const SurfaceTerms& terms);

}  // namespace softsim::fit
