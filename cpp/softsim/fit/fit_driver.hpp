#pragma once
// The whole fitting procedure of 002 §3 for up to three load directions: for each direction,
// from the dataset of forces along it, choose the orders of relations 1–3 by cross-validation
// (unless fixed), fit them with Levenberg–Marquardt and assemble the FitModel.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "softsim/fit/dataset.hpp"
#include "softsim/fit/model.hpp"
#include "softsim/fit/relations.hpp"

namespace softsim::fit {

// Candidate orders examined by cross-validation: 0..max for each.
struct OrderLimits {
  int force = 4;         // relation 1
  int surface_x = 8;     // separable a
  int surface_y = 8;     // separable b
  int bivariate = 8;     // total degree n
  int trivariate = 8;    // total degree n of the x–y–z surfaces
  int parameter = 3;     // relation 3
};

// Which surface models compete in the choice of relation 2. `best` pools separable, bivariate
// and, where the surface nodes span z (nodes_span_z), trivariate candidates.
enum class SurfaceChoice { separable, bivariate, trivariate, best };

const char* to_string(SurfaceChoice choice);

// Orders fixed by the user; an unset order is chosen by cross-validation.
struct ComponentOrders {
  std::optional<SurfaceTerms> surface;
  std::optional<int> parameter_order;
};
struct DirectionOrders {
  std::optional<int> force_order;
  std::array<ComponentOrders, 3> components;
};

struct FitSettings {
  FitOptions options;
  bool loaded_node_from_relation1 = true;  // see FitModel
  SurfaceChoice surface_choice = SurfaceChoice::separable;
  OrderLimits limits;
  std::array<DirectionOrders, 3> fixed;
};

struct CvCandidate {
  int order = 0;          // relations 1 and 3
  SurfaceTerms surface;   // relation 2
  CvScore score;
};

enum class Relation { force_to_loaded, surface, parameters };

const char* to_string(Relation relation);

// Every candidate of one relation for one (direction, component).
struct CvTable {
  Relation relation = Relation::force_to_loaded;
  int direction = 0;
  int component = -1;  // -1 for relation 1
  std::optional<SurfaceModel> model;  // relation 2: the model family of this table
  std::vector<CvCandidate> candidates;
  int chosen = -1;     // index of the candidate the fitted model uses; -1: none from this table
  int preferred = -1;  // the candidate this table alone would choose (compares model families)
  double exact_floor_mse = 0.0;
};

// How an order came about and the diagnostics of the final fit.
struct Choice {
  std::string source;  // "cv" or "config"
  std::optional<CvScore> score;  // the chosen candidate's CV score (source "cv")
  int candidates = 0;
  int refused = 0;
};

struct ComponentReport {
  Choice surface_choice;
  Choice parameter_choice;
  FitSummary surface_fit;
  FitSummary parameter_fit;
};

struct DirectionReport {
  std::string dataset;
  int cases = 0;
  Choice force_choice;
  LinearFit force_fit;  // with the damping history
  std::array<ComponentReport, 3> components;
};

struct FitResult {
  FitModel model;
  std::vector<CvTable> cv_tables;
  std::array<DirectionReport, 3> reports;
};

// datasets[d]: the dataset of forces along axis d, or nullptr when direction d is not fitted.
// With cv_every_model the surface CV covers every model family (trivariate where the nodes span z,
// or where it is the chosen family) and fixed orders are
// cross-validated too (the `cv` mode); otherwise only what a choice needs is computed.
// Throws InputError for inconsistent datasets, NumericalError when a final fit fails or no
// candidate order is admissible.
FitResult fit_surface_model(const std::array<const Dataset*, 3>& datasets, const FitSettings& settings,
                            bool cv_every_model);

}  // namespace softsim::fit
