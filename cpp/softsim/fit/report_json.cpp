#include "softsim/fit/report_json.hpp"

#include <cmath>

#include "softsim/fit/model_json.hpp"
#include "softsim/fit/paper_units.hpp"
#include "softsim/fit/settings_json.hpp"

namespace softsim::fit {

namespace {

nlohmann::json vec3(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

nlohmann::json choice_to_json(const Choice& c) {
  nlohmann::json j = {{"source", c.source}};
  if (c.source == "cv") {
    j["candidates"] = c.candidates;
    j["refused"] = c.refused;
  }
  if (c.score) j["cv"] = cv_score_to_json(*c.score);
  return j;
}

nlohmann::json summary_to_json(const FitSummary& s) {
  return {{"condition", finite_or_null(s.condition)},
          {"samples", s.samples},
          {"parameters", s.parameters},
          {"max_iterations", s.max_iterations},
          {"termination", s.termination},
          {"rmse", s.rmse}};
}

nlohmann::json linear_fit_to_json(const LinearFit& f) {
  nlohmann::json history = nlohmann::json::array();
  for (const auto& it : f.history)
    history.push_back({{"iteration", it.iteration}, {"cost", it.cost}, {"damping", it.damping}, {"accepted", it.accepted}});
  return {{"condition", finite_or_null(f.condition)},
          {"iterations", f.iterations},
          {"termination", f.termination},
          {"initial_cost", f.initial_cost},
          {"final_cost", f.final_cost},
          {"damping_history", history}};
}

}  // namespace

nlohmann::json cv_score_to_json(const CvScore& s) {
  nlohmann::json j = {{"status", to_string(s.status)},
                      {"parameters", s.parameters},
                      {"max_condition", finite_or_null(s.max_condition)}};
  if (s.ok()) {
    j["mse"] = s.mse;
    j["rmse"] = std::sqrt(s.mse);
    j["se"] = s.se;
    j["predictions"] = s.predictions;
  } else {
    j["mse"] = nullptr;
    j["rmse"] = nullptr;
    j["message"] = s.message;
  }
  return j;
}

nlohmann::json cv_table_to_json(const CvTable& t) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t i = 0; i < t.candidates.size(); ++i) {
    const CvCandidate& c = t.candidates[i];
    nlohmann::json row = cv_score_to_json(c.score);
    if (t.relation == Relation::surface) {
      row["surface"] = surface_terms_to_json(c.surface);
      row["label"] = c.surface.label();
    } else {
      row["order"] = c.order;
      row["label"] = std::to_string(c.order);
    }
    row["chosen"] = static_cast<int>(i) == t.chosen;
    row["preferred"] = static_cast<int>(i) == t.preferred;
    rows.push_back(row);
  }
  nlohmann::json j = {{"relation", to_string(t.relation)},
                      {"direction", kAxis[t.direction]},
                      {"component", t.component >= 0 ? nlohmann::json(kAxis[t.component]) : nlohmann::json(nullptr)},
                      {"model", t.model ? nlohmann::json(to_string(*t.model)) : nlohmann::json(nullptr)},
                      {"exact_floor_mse", t.exact_floor_mse},
                      {"candidates", rows}};
  return j;
}

nlohmann::json selection_to_json(const FitResult& r) {
  nlohmann::json out = nlohmann::json::object();
  for (int d = 0; d < 3; ++d) {
    const DirectionModel& dm = r.model.directions[d];
    if (!dm.present) continue;
    const DirectionReport& rep = r.reports[d];
    nlohmann::json comps = nlohmann::json::object();
    for (int c = 0; c < 3; ++c) {
      const ComponentModel& cm = dm.components[c];
      const ComponentReport& cr = rep.components[c];
      comps[kAxis[c]] = {{"surface", surface_terms_to_json(cm.surface)},
                         {"surface_label", cm.surface.label()},
                         {"surface_terms", cm.surface.size()},
                         {"surface_choice", choice_to_json(cr.surface_choice)},
                         {"surface_fit", summary_to_json(cr.surface_fit)},
                         {"parameter_order", cm.parameter_order},
                         {"parameter_choice", choice_to_json(cr.parameter_choice)},
                         {"parameter_fit", summary_to_json(cr.parameter_fit)}};
    }
    out[kAxis[d]] = {{"dataset", rep.dataset},
                     {"cases", rep.cases},
                     {"force_order", dm.force_to_loaded.order()},
                     {"force_choice", choice_to_json(rep.force_choice)},
                     {"force_fit", linear_fit_to_json(rep.force_fit)},
                     {"components", comps}};
  }
  return out;
}

nlohmann::json paper_units_to_json(const FitModel& model) {
  nlohmann::json out = nlohmann::json::object();
  for (int d = 0; d < 3; ++d) {
    const DirectionModel& dm = model.directions[d];
    if (!dm.present) continue;
    const Eigen::VectorXd r = force_relation_in_mm(dm);
    nlohmann::json comps = nlohmann::json::object();
    for (int c = 0; c < 3; ++c) {
      const ComponentModel& cm = dm.components[c];
      if (cm.surface.model == SurfaceModel::zero) {
        comps[kAxis[c]] = {{"surface", surface_terms_to_json(cm.surface)}, {"terms", nlohmann::json::array()}};
        continue;
      }
      const PaperSurface ps = surface_in_mm(model, d, c);
      nlohmann::json terms = nlohmann::json::array();
      for (std::size_t t = 0; t < ps.powers.size(); ++t) {
        const Eigen::VectorXd b = ps.beta.row(static_cast<Eigen::Index>(t)).transpose();
        nlohmann::json term = {{"x_power", ps.powers[t][0]},
                               {"y_power", ps.powers[t][1]},
                               {"beta", std::vector<double>(b.data(), b.data() + b.size())}};
        if (cm.surface.model == SurfaceModel::trivariate) term["z_power"] = ps.powers[t][2];
        terms.push_back(term);
      }
      comps[kAxis[c]] = {{"surface", surface_terms_to_json(cm.surface)}, {"terms", terms}};
    }
    out[kAxis[d]] = {{"units", "displacement mm, force N, x and y in mm from the plate corner"},
                     {"force_to_loaded_mm_per_N_power", std::vector<double>(r.data(), r.data() + r.size())},
                     {"components", comps}};
  }
  return out;
}

nlohmann::json errors_to_json(const ComponentErrors& e) {
  return {{"rmse", vec3(e.rmse)},
          {"max_abs", vec3(e.max_abs)},
          {"mean", vec3(e.mean)},
          {"reference_rms", vec3(e.reference_rms)},
          {"samples", e.samples}};
}

nlohmann::json rows_to_json(const Eigen::MatrixXd& m) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index j = 0; j < m.rows(); ++j) out.push_back({m(j, 0), m(j, 1), m(j, 2)});
  return out;
}

}  // namespace softsim::fit
