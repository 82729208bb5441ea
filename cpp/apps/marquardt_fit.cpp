// marquardt_fit: Levenberg–Marquardt fits of the surface displacement against the force with
// cross-validated orders (002 §2.4, §3), and their real-time playback.
//   fit   datasets -> "marquardt_fit" artifact (model, chosen orders, errors, timing)
//   cv    datasets -> "marquardt_cv" artifact (CV score of every candidate order, both surface models)
//   play  fit artifact + forces -> "surface_playback" artifact
#include <chrono>
#include <iostream>

#include "common/app.hpp"
#include "softsim/fit/assessment.hpp"
#include "softsim/fit/dataset_json.hpp"
#include "softsim/fit/fit_config.hpp"
#include "softsim/fit/fit_driver.hpp"
#include "softsim/fit/model_json.hpp"
#include "softsim/fit/report_json.hpp"
#include "softsim/fit/settings_json.hpp"
#include "softsim/fit/surface_playback.hpp"

using namespace softsim;

namespace {

void fit_or_cv(app::AppContext& ctx) {
  const bool cv_mode = ctx.mode == "cv";
  const fit::FitConfig config = fit::read_fit_config(ctx.config(), cv_mode);
  const fit::FitSettings& settings = config.settings;
  const auto& paths = config.datasets;
  const auto& series = config.series;

  std::array<fit::Dataset, 3> data;
  std::array<const fit::Dataset*, 3> use = {nullptr, nullptr, nullptr};
  nlohmann::json sources = nlohmann::json::object(), dataset_timing = nlohmann::json::object();
  for (int d = 0; d < 3; ++d) {
    if (paths[d].path.empty()) continue;
    if (series[d]) {
      ctx.input(series[d]->mesh);
      for (const auto& c : series[d]->cases) ctx.input(c.result);
      data[d] = fit::read_static_series(*series[d]);
    } else {
      ctx.input(paths[d].path);
      data[d] = fit::read_dataset(paths[d]);
    }
    use[d] = &data[d];
    sources[fit::kAxis[d]] = {{"path", paths[d].path}, {"kind", data[d].kind}, {"cases", data[d].case_count()}};
    if (!paths[d].member.empty()) sources[fit::kAxis[d]]["member"] = paths[d].member;
    dataset_timing[fit::kAxis[d]] = data[d].timing;
  }
  ctx.provenance.seed = settings.options.seed;
  const auto fit_start = std::chrono::steady_clock::now();
  const fit::FitResult result = fit::fit_surface_model(use, settings, cv_mode);
  // The precompute's second half (002 §5.1.2 times only the playback): cross-validation and fits.
  const double fit_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - fit_start).count();
  nlohmann::json payload = {{"settings", fit::fit_settings_to_json(settings)},
                            {"datasets", sources},
                            {"selection", fit::selection_to_json(result)}};
  if (cv_mode) {
    nlohmann::json tables = nlohmann::json::array();
    for (const auto& t : result.cv_tables) tables.push_back(fit::cv_table_to_json(t));
    payload["tables"] = tables;
    ctx.write("marquardt_cv", 1, std::move(payload));
    std::cerr << "marquardt_fit cv: " << result.cv_tables.size() << " tables\n";
    return;
  }

  std::optional<fit::Superposition> exact;
  nlohmann::json training = nlohmann::json::object(), checks = nullptr;
  for (int d = 0; d < 3; ++d) {
    if (use[d] == nullptr) continue;
    training[fit::kAxis[d]] = fit::assess_dataset(result.model, data[d], 0);
    if (!exact && data[d].unit_solutions) exact.emplace(*data[d].unit_solutions);
  }
  nlohmann::json validated = nlohmann::json::array();
  for (const auto& ref : config.validation) {
    ctx.input(ref.path);
    const fit::Dataset v = fit::read_dataset(ref);
    fit::require_same_nodes(v, result.model);
    validated.push_back(fit::assess_dataset(result.model, v, config.examples));
    if (!exact && v.unit_solutions) exact.emplace(*v.unit_solutions);
  }
  if (exact) checks = fit::check_against_superposition(result.model, *exact, config.check_forces);
  payload["model"] = fit::model_to_json(result.model);
  payload["paper_units"] = fit::paper_units_to_json(result.model);
  payload["training"] = training;
  payload["validation"] = validated;
  payload["check"] = checks;
  payload["timing"] = config.evaluations > 0 ? fit::measure_evaluation_time(result.model, exact, config.evaluations) : nlohmann::json(nullptr);
  payload["dataset_timing"] = dataset_timing;
  payload["fit_seconds"] = fit_seconds;
  ctx.write(fit::kFitSchema, fit::kFitSchemaVersion, std::move(payload));
  std::cerr << "marquardt_fit: fitted " << sources.size() << " load directions\n";
}

void play(app::AppContext& ctx) {
  const fit::PlaybackConfig config = fit::read_playback_config(ctx.config());
  ctx.input(config.fit_path);
  if (!config.reference.path.empty()) ctx.input(config.reference.path);
  ctx.write(fit::kPlaybackSchema, fit::kPlaybackSchemaVersion, fit::play_back(config));
  std::cerr << "marquardt_fit play: " << config.forces.size() << " forces\n";
}

}  // namespace

int main(int argc, char** argv) {
  app::AppInfo info;
  info.name = "marquardt_fit";
  info.summary = "Levenberg–Marquardt surface fits with cross-validated orders (002 §3); fit, cv or play back";
  info.modes = {"fit", "cv", "play"};
  // The defaults shown are the config structs' own (fit_config.hpp), not copies.
  const fit::FitConfig config;
  const nlohmann::json defaults = fit::fit_settings_to_json(config.settings);
  info.config_help =
      "  fit, cv: {\"datasets\": {\"x\": \"axis_x.json\", \"y\": ..., \"z\": ...},   rpim_dataset artifacts, forces along each axis,\n"
      "            or {\"kind\": \"static_series\", \"mesh\": ..., \"loaded_point\": [x, y, z], \"cases\": [{\"result\": ..., \"force\": [..]}]}\n"
      "            \"basis\": \"legendre\"|\"monomial\", \"input_scaling\": \"unit_interval\"|\"none\",\n"
      "            \"surface_model\": \"separable\"|\"bivariate\"|\"trivariate\"|\"best\", \"loaded_node_displacement\": \"relation1\"|\"surface\",\n"
      "            \"cv\": " + defaults["cv"].dump() + " (selection: \"one_se\"|\"min\"),\n"
      "            \"solver\": " + defaults["solver"].dump() + ",\n"
      "            \"orders\": {\"z\": {\"force\": 1, \"components\": {\"x\": {\"surface\": {\"model\": \"separable\", \"orders\": [5, 1]}, \"parameters\": 1}}}},\n"
      "            fit only: \"validation\": [\"random.json\"], \"check_forces\": " + nlohmann::json(config.check_forces).dump() +
      " (N), \"examples\": " + std::to_string(config.examples) + ",\n"
      "                      \"timing\": {\"evaluations\": " + std::to_string(config.evaluations) + "}}\n"
      "  play:    {\"fit\": \"fit.json\", \"forces\": [[fx, fy, fz], ...] (N), \"reference\": \"dataset.json\" (optional)}\n"
      "  See cpp/apps/marquardt_fit.md.";
  return app::run_app(argc, argv, info, [](app::AppContext& ctx) {
    if (ctx.mode == "play")
      play(ctx);
    else
      fit_or_cv(ctx);
  });
}
