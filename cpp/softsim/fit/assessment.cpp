#include "softsim/fit/assessment.hpp"

#include <chrono>
#include <cmath>

#include "softsim/fit/evaluation.hpp"
#include "softsim/fit/playback.hpp"
#include "softsim/fit/report_json.hpp"

namespace softsim::fit {

namespace {

Eigen::MatrixXd node_major_to_rows(const Eigen::VectorXd& u) {
  const Eigen::Index n = u.size() / 3;
  Eigen::MatrixXd rows(n, 3);
  for (Eigen::Index j = 0; j < n; ++j) rows.row(j) << u[3 * j], u[3 * j + 1], u[3 * j + 2];
  return rows;
}

nlohmann::json vec3(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

}  // namespace

nlohmann::json assess_dataset(const FitModel& model, const Dataset& data, int examples) {
  const SurfacePlayer player(model);
  const int n = player.node_count();
  std::optional<Superposition> exact;
  if (data.unit_solutions) exact.emplace(*data.unit_solutions);
  ErrorAccumulator fit_vs_data(n), sup_vs_data(n), fit_vs_sup(n);
  Eigen::VectorXd u(3 * n), s(3 * n);
  nlohmann::json per_case = nlohmann::json::array(), example_fields = nlohmann::json::array();
  for (int i = 0; i < data.case_count(); ++i) {
    const LoadCase& lc = data.cases[i];
    player.play(lc.force, u.data());
    ErrorAccumulator one(n);
    one.add(u.data(), lc.displacement);
    fit_vs_data.add(u.data(), lc.displacement);
    const ComponentErrors e = one.result();
    const Eigen::Index c = model.loaded_node;
    nlohmann::json row = {{"force", vec3(lc.force)},
                          {"fit_rmse", vec3(e.rmse)},
                          {"fit_max_abs", vec3(e.max_abs)},
                          {"data_rms", vec3(e.reference_rms)},
                          {"loaded_node_fit", {u[3 * c], u[3 * c + 1], u[3 * c + 2]}},
                          {"loaded_node_data", vec3(lc.displacement.row(c).transpose())}};
    if (exact) {
      exact->apply(lc.force, s.data());
      sup_vs_data.add(s.data(), lc.displacement);
      fit_vs_sup.add(u.data(), node_major_to_rows(s));
      ErrorAccumulator sd(n);
      sd.add(s.data(), lc.displacement);
      row["superposition_max_abs"] = vec3(sd.result().max_abs);
    }
    per_case.push_back(row);
    if (i < examples)
      example_fields.push_back({{"force", vec3(lc.force)},
                                {"fit", rows_to_json(node_major_to_rows(u))},
                                {"data", rows_to_json(lc.displacement)}});
  }
  nlohmann::json out = {{"dataset", data.source},
                        {"kind", data.kind},
                        {"cases", data.case_count()},
                        {"fit_vs_data", errors_to_json(fit_vs_data.result())},
                        {"per_case", per_case},
                        {"examples", example_fields}};
  if (exact) {
    out["superposition_vs_data"] = errors_to_json(sup_vs_data.result());
    out["fit_vs_superposition"] = errors_to_json(fit_vs_sup.result());
  }
  return out;
}

nlohmann::json check_against_superposition(const FitModel& model, const Superposition& exact,
                                           const std::vector<double>& forces) {
  const SurfacePlayer player(model);
  const int n = player.node_count();
  Eigen::VectorXd u(3 * n), s(3 * n);
  nlohmann::json out = nlohmann::json::object();
  for (int d = 0; d < 3; ++d) {
    if (!model.directions[d].present) continue;
    ErrorAccumulator all(n);
    Eigen::Vector3d rmse_per_newton = Eigen::Vector3d::Zero();
    nlohmann::json per_force = nlohmann::json::array();
    int counted = 0;
    for (double F : forces) {
      Eigen::Vector3d f = Eigen::Vector3d::Zero();
      f[d] = F;
      player.play(f, u.data());
      exact.apply(f, s.data());
      const Eigen::MatrixXd reference = node_major_to_rows(s);
      all.add(u.data(), reference);
      ErrorAccumulator one(n);
      one.add(u.data(), reference);
      const ComponentErrors e = one.result();
      if (F != 0.0) {
        rmse_per_newton += e.rmse / std::abs(F);
        ++counted;
      }
      nlohmann::json row = errors_to_json(e);
      row["force"] = F;
      per_force.push_back(row);
    }
    if (counted > 0) rmse_per_newton /= counted;
    out[kAxis[d]] = {{"forces", forces},
                     {"errors", errors_to_json(all.result())},
                     {"rmse_per_newton", vec3(rmse_per_newton)},
                     {"per_force", per_force},
                     {"mean_deviation", rows_to_json(all.mean_deviation())}};
  }
  return out;
}

nlohmann::json measure_evaluation_time(const FitModel& model, const std::optional<Superposition>& exact,
                                       long evaluations) {
  const SurfacePlayer player(model);
  const int n = player.node_count();
  Eigen::VectorXd u(3 * n);
  // A fixed cycle of forces so that no evaluation can be hoisted out of the loop.
  std::vector<Eigen::Vector3d> forces;
  for (int k = 0; k < 64; ++k)
    forces.emplace_back(std::sin(0.7 * k), std::cos(1.3 * k), -std::abs(std::sin(0.37 * k + 0.2)));
  using clock = std::chrono::steady_clock;
  double checksum = 0.0;
  auto time_it = [&](auto&& evaluate) {
    evaluate(forces[0]);  // warm-up
    const auto t0 = clock::now();
    for (long i = 0; i < evaluations; ++i) {
      evaluate(forces[static_cast<std::size_t>(i) % forces.size()]);
      checksum += u[static_cast<Eigen::Index>(i % (3 * n))];
    }
    return std::chrono::duration<double>(clock::now() - t0).count() / static_cast<double>(evaluations);
  };
  nlohmann::json out = {{"evaluations", evaluations}, {"nodes", n}};
  out["playback_s_per_evaluation"] = time_it([&](const Eigen::Vector3d& f) { player.play(f, u.data()); });
  if (exact)
    out["superposition_s_per_evaluation"] = time_it([&](const Eigen::Vector3d& f) { exact->apply(f, u.data()); });
  volatile double sink = checksum;  // keeps the evaluations observable to the optimiser
  (void)sink;
  return out;
}

}  // namespace softsim::fit
