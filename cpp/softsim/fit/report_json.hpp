#pragma once
// JSON views of the fitting procedure for the artifacts: cross-validation tables, how each order
// was chosen, final-fit diagnostics (condition, iterations, damping history), error statistics
// and the paper-unit coefficient tables.
#include <nlohmann/json.hpp>

#include "softsim/fit/evaluation.hpp"
#include "softsim/fit/fit_driver.hpp"

namespace softsim::fit {

nlohmann::json cv_score_to_json(const CvScore& score);
nlohmann::json cv_table_to_json(const CvTable& table);
// The per-direction choices and diagnostics ("selection" of the fit artifact).
nlohmann::json selection_to_json(const FitResult& result);
// Relation 1 and the surfaces in the paper's units (mm, N; x and y from the plate corner).
nlohmann::json paper_units_to_json(const FitModel& model);
nlohmann::json errors_to_json(const ComponentErrors& errors);
// nodes × 3 matrix as [[ux, uy, uz], ...].
nlohmann::json rows_to_json(const Eigen::MatrixXd& rows);

}  // namespace softsim::fit
