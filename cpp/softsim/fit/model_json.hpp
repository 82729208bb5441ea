#pragma once
// The fitted model inside a "marquardt_fit" artifact (payload member "model"): everything the
// playback needs, in the internal scaled basis, SI units. Read back strictly.
#include <string>

#include <nlohmann/json.hpp>

#include "softsim/fit/model.hpp"
#include "softsim/io/json_reader.hpp"

namespace softsim::fit {

inline constexpr const char* kFitSchema = "marquardt_fit";
inline constexpr int kFitSchemaVersion = 1;

nlohmann::json model_to_json(const FitModel& model);
FitModel model_from_json(const io::JsonReader& node);

// Reads the "model" member of a marquardt_fit artifact.
FitModel read_fit_model(const std::string& path);

nlohmann::json scale_to_json(const AffineScale& scale);

// A number for JSON: non-finite values (a singular design's condition) become null.
nlohmann::json finite_or_null(double value);

}  // namespace softsim::fit
