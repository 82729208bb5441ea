#pragma once
// How good is a fitted model? Errors against RPIM load cases and against the exact
// superposition baseline, the paper's check of §5.1.1 (forces of 0.2 ... 1.0 N along each axis:
// RMSE per component, Table 3, and mean deviation maps, Figs. 5–13) and the time per playback.
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "softsim/fit/dataset.hpp"
#include "softsim/fit/model.hpp"
#include "softsim/fit/superposition.hpp"

namespace softsim::fit {

// Every case of `data` played back and compared with the data; with unit solutions also the
// superposition against the data and the fit against the superposition. The first `examples`
// cases carry their full fields (fit and data) for plots.
nlohmann::json assess_dataset(const FitModel& model, const Dataset& data, int examples);

// For each fitted direction d and each magnitude F of `forces` (N): the fit at F e_d against
// the exact superposition; aggregated RMSE per component, RMSE per newton, mean deviation of
// every node over the forces.
nlohmann::json check_against_superposition(const FitModel& model, const Superposition& exact,
                                           const std::vector<double>& forces);

// Wall-clock seconds per evaluation of all surface nodes, averaged over `evaluations` calls on
// varying forces: playback, and the superposition when given.
nlohmann::json measure_evaluation_time(const FitModel& model, const std::optional<Superposition>& exact,
                                       long evaluations);

}  // namespace softsim::fit
