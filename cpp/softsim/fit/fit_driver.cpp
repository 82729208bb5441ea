#include "softsim/fit/fit_driver.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <tuple>

#include "softsim/io/errors.hpp"

namespace softsim::fit {

const char* to_string(SurfaceChoice choice) {
  switch (choice) {
    case SurfaceChoice::separable: return "separable";
    case SurfaceChoice::bivariate: return "bivariate";
    case SurfaceChoice::trivariate: return "trivariate";
    case SurfaceChoice::best: return "best";
  }
  return "unknown";
}

const char* to_string(Relation relation) {
  switch (relation) {
    case Relation::force_to_loaded: return "force_to_loaded";
    case Relation::surface: return "surface";
    case Relation::parameters: return "parameters";
  }
  return "unknown";
}

namespace {

void check_datasets(const std::array<const Dataset*, 3>& datasets) {
  const Dataset* first = nullptr;
  for (int d = 0; d < 3; ++d) {
    const Dataset* ds = datasets[d];
    if (ds == nullptr) continue;
    if (ds->cases.empty()) throw InputError(ds->source + ": /payload/cases: expected at least one load case");
    if (ds->node_count() == 0) throw InputError(ds->source + ": /payload/top_nodes: expected surface nodes");
    if (off_axis_fraction(*ds, d) > 1e-9)
      throw InputError(ds->source + ": /payload/cases: expected every force along " + kAxis[d] +
                       " for the " + kAxis[d] + " relations");
    if (first == nullptr) {
      first = ds;
      continue;
    }
    if (!same_surface(first->nodes, ds->nodes))
      throw InputError(ds->source + ": /payload/top_nodes: expected the same surface nodes as " + first->source);
    if (ds->loaded_node != first->loaded_node)
      throw InputError(ds->source + ": /payload/loaded_node: expected the same loaded node as " + first->source);
  }
  if (first == nullptr) throw InputError("no dataset to fit: expected at least one of the x, y, z datasets");
}

Eigen::MatrixXd component_values(const Dataset& ds, int component) {
  Eigen::MatrixXd v(ds.node_count(), ds.case_count());
  for (int i = 0; i < ds.case_count(); ++i) v.col(i) = ds.cases[i].displacement.col(component);
  return v;
}

std::string name(int d, int c, const char* relation) {
  std::string s = std::string(relation) + ", force along " + kAxis[d];
  if (c >= 0) s += std::string(", displacement ") + kAxis[c];
  return s;
}

// Fills a Choice from the table's chosen row; throws when nothing was admissible.
Choice chosen_from(const CvTable& table, int chosen_index, const std::string& what) {
  Choice ch;
  ch.source = "cv";
  ch.candidates = static_cast<int>(table.candidates.size());
  for (const auto& c : table.candidates) ch.refused += c.score.ok() ? 0 : 1;
  if (chosen_index < 0) {
    std::string reason = table.candidates.empty() ? "no candidates" : table.candidates.front().score.message;
    throw NumericalError(what + ": every candidate order was refused by cross-validation (first: " + reason + ")");
  }
  ch.score = table.candidates[chosen_index].score;
  return ch;
}

Choice from_config() {
  Choice ch;
  ch.source = "config";
  return ch;
}

std::vector<int> complexities(const std::vector<CvCandidate>& c, bool by_parameters) {
  std::vector<int> out;
  for (const auto& x : c) out.push_back(by_parameters ? x.score.parameters : x.order);
  return out;
}

CvCandidate order_candidate(int order, CvScore score) {
  CvCandidate c;
  c.order = order;
  c.score = std::move(score);
  return c;
}

CvCandidate surface_candidate(const SurfaceTerms& terms, CvScore score) {
  CvCandidate c;
  c.surface = terms;
  c.score = std::move(score);
  return c;
}

std::vector<CvScore> scores_of(const std::vector<CvCandidate>& c) {
  std::vector<CvScore> out;
  for (const auto& x : c) out.push_back(x.score);
  return out;
}

// The order of relation 1 or 3: the configured one, or the one cross-validation chooses among
// 0..max_order (scored by score_order(k)); `choice` says which. When CV runs, its table joins
// `tables`; for a configured order (cv_every_model) it shows the preferred row but none chosen.
template <class ScoreOrder>
int choose_order(CvTable table, int max_order, const std::optional<int>& fixed_order, bool cv_every_model,
                 Selection selection, const std::string& what, ScoreOrder&& score_order, Choice& choice,
                 std::vector<CvTable>& tables) {
  int order = fixed_order.value_or(0);
  if (!fixed_order || cv_every_model) {
    for (int k = 0; k <= max_order; ++k) table.candidates.push_back(order_candidate(k, score_order(k)));
    table.chosen = select_candidate(scores_of(table.candidates), complexities(table.candidates, false), selection,
                                    table.exact_floor_mse);
    table.preferred = table.chosen;
    if (!fixed_order) {
      choice = chosen_from(table, table.chosen, what);
      order = table.candidates[table.chosen].order;
    } else {
      table.chosen = -1;
    }
    tables.push_back(std::move(table));
  }
  if (fixed_order) choice = from_config();
  return order;
}

// The surface CV of every candidate, built on first use and shared by every direction and
// component: it depends on the terms and the model's nodes only, which every direction uses.
class SurfaceCvCache {
 public:
  SurfaceCvCache(const SurfaceFrame& frame, const Eigen::MatrixXd& xy, const FitOptions& options)
      : frame_(frame), xy_(xy), options_(options) {}

  CvScore score(const SurfaceTerms& terms, const Eigen::MatrixXd& values) {
    const std::tuple<SurfaceModel, int, int, int, int> key{terms.model, terms.order_x, terms.order_y, terms.degree,
                                                           terms.z_degree};
    auto it = cache_.find(key);
    if (it == cache_.end()) it = cache_.emplace(key, SurfaceCv(terms, frame_, xy_, options_)).first;
    return it->second.score(values);
  }

 private:
  const SurfaceFrame& frame_;
  const Eigen::MatrixXd& xy_;
  const FitOptions& options_;
  std::map<std::tuple<SurfaceModel, int, int, int, int>, SurfaceCv> cache_;
};

}  // namespace

FitResult fit_surface_model(const std::array<const Dataset*, 3>& datasets, const FitSettings& settings,
                            bool cv_every_model) {
  check_datasets(datasets);
  const FitOptions& opt = settings.options;
  const OrderLimits& lim = settings.limits;

  const Dataset* reference = nullptr;
  for (const Dataset* ds : datasets)
    if (ds != nullptr && reference == nullptr) reference = ds;

  FitResult result;
  FitModel& model = result.model;
  model.nodes = reference->nodes;
  model.loaded_node = reference->loaded_node;
  model.scaled_inputs = opt.scale_inputs;
  model.loaded_node_from_relation1 = settings.loaded_node_from_relation1;
  model.frame.basis = opt.basis;
  {
    std::vector<double> xs, ys, zs;
    for (Eigen::Index r = 0; r < model.nodes.rows(); ++r) {
      xs.push_back(model.nodes(r, 0));
      ys.push_back(model.nodes(r, 1));
      zs.push_back(model.nodes(r, 2));
    }
    model.frame.x = input_scale(xs, opt.scale_inputs);
    model.frame.y = input_scale(ys, opt.scale_inputs);
    model.frame.z = input_scale(zs, opt.scale_inputs);
  }
  // On nodes in one plane z = const the trivariate candidates are the bivariate ones
  // (surface_basis.hpp); `best` and the cv mode then leave them out instead of repeating those.
  const bool spans_z = nodes_span_z(model.nodes);
  const int z_cap = spans_z ? kMaxOrder : 0;
  const Eigen::MatrixXd& xy = model.nodes;
  SurfaceCvCache surface_cv(model.frame, xy, opt);

  for (int d = 0; d < 3; ++d) {
    const Dataset* ds = datasets[d];
    if (ds == nullptr) continue;
    DirectionModel& dm = model.directions[d];
    DirectionReport& rep = result.reports[d];
    const DirectionOrders& fixed = settings.fixed[d];
    dm.present = true;
    rep.dataset = ds->source;
    rep.cases = ds->case_count();

    // ---- relation 1 (002 eqs. 39–42) ----
    const std::vector<double> force = force_components(*ds, d);
    const std::vector<double> delta = loaded_displacements(*ds, d);
    const AffineScale force_scale = input_scale(force, opt.scale_inputs);
    const std::string what1 = name(d, -1, "relation 1 (loaded-node displacement)");
    // Forces that take one value (all zero, all the same) say nothing of how the displacement
    // depends on the force: whatever order CV chose, playback would give every force that one
    // displacement. The fixed-order path finds the same as an ill-conditioned design.
    if (std::adjacent_find(force.begin(), force.end(), std::not_equal_to<>()) == force.end())
      throw NumericalError(what1 + ": ill_conditioned: every case has the force " + std::to_string(force.front()) +
                           " N: expected at least two different forces");
    CvTable force_table;
    force_table.relation = Relation::force_to_loaded;
    force_table.direction = d;
    const Eigen::Map<const Eigen::VectorXd> dv(delta.data(), static_cast<Eigen::Index>(delta.size()));
    force_table.exact_floor_mse = exact_floor_mse(dv, opt.exact_relative);
    const int force_order = choose_order(
        std::move(force_table), lim.force, fixed.force_order, cv_every_model, opt.selection, what1,
        [&](int k) { return cv_polynomial(force, delta, k, force_scale, opt); }, rep.force_choice, result.cv_tables);
    {
      FitOptions o = opt;
      o.lm.record_history = true;
      rep.force_fit = fit_polynomial(force, delta, force_order, force_scale, o);
      require_ok(rep.force_fit, what1 + ", order " + std::to_string(force_order));
      dm.force_to_loaded.basis = opt.basis;
      dm.force_to_loaded.scale = force_scale;
      dm.force_to_loaded.coefficients = rep.force_fit.coefficients;
    }
    dm.delta_scale = input_scale(delta, opt.scale_inputs);

    for (int c = 0; c < 3; ++c) {
      ComponentModel& cm = dm.components[c];
      ComponentReport& crep = rep.components[c];
      const ComponentOrders& cfix = fixed.components[c];
      const Eigen::MatrixXd values = component_values(*ds, c);
      const double floor = exact_floor_mse(values, opt.exact_relative);

      // ---- relation 2 (002 eqs. 43–44) ----
      const std::string what2 = name(d, c, "relation 2 (surface)");
      const bool need_choice = !cfix.surface.has_value();
      const bool want_sep = cv_every_model || (need_choice && (settings.surface_choice == SurfaceChoice::separable ||
                                                               settings.surface_choice == SurfaceChoice::best));
      const bool want_biv = cv_every_model || (need_choice && (settings.surface_choice == SurfaceChoice::bivariate ||
                                                               settings.surface_choice == SurfaceChoice::best));
      const bool want_tri = settings.surface_choice == SurfaceChoice::trivariate
                                ? (cv_every_model || need_choice)
                                : (spans_z && (cv_every_model || (need_choice && settings.surface_choice == SurfaceChoice::best)));
      std::vector<CvTable> surface_tables;
      if (want_sep) {
        CvTable t;
        t.relation = Relation::surface;
        t.model = SurfaceModel::separable;
        for (int a = 0; a <= lim.surface_x; ++a)
          for (int b = 0; b <= lim.surface_y; ++b) {
            const SurfaceTerms terms = SurfaceTerms::separable(a, b);
            t.candidates.push_back(surface_candidate(terms, surface_cv.score(terms, values)));
          }
        surface_tables.push_back(std::move(t));
      }
      if (want_biv) {
        CvTable t;
        t.relation = Relation::surface;
        t.model = SurfaceModel::bivariate;
        for (int n = 0; n <= lim.bivariate; ++n) {
          const SurfaceTerms terms = SurfaceTerms::bivariate(n);
          t.candidates.push_back(surface_candidate(terms, surface_cv.score(terms, values)));
        }
        surface_tables.push_back(std::move(t));
      }
      if (want_tri) {
        CvTable t;
        t.relation = Relation::surface;
        t.model = SurfaceModel::trivariate;
        for (int n = 0; n <= lim.trivariate; ++n) {
          const SurfaceTerms terms = SurfaceTerms::trivariate(n, std::min(n, z_cap));
          t.candidates.push_back(surface_candidate(terms, surface_cv.score(terms, values)));
        }
        surface_tables.push_back(std::move(t));
      }
      for (auto& t : surface_tables) {
        t.direction = d;
        t.component = c;
        t.exact_floor_mse = floor;
        t.preferred = select_candidate(scores_of(t.candidates), complexities(t.candidates, true),
                                       opt.selection, floor);
      }
      if (need_choice) {
        // Pool the candidates of the competing model families and choose once.
        std::vector<CvCandidate> pool;
        std::vector<std::pair<int, int>> origin;
        for (int ti = 0; ti < static_cast<int>(surface_tables.size()); ++ti) {
          const SurfaceModel m = *surface_tables[ti].model;
          const bool allowed = settings.surface_choice == SurfaceChoice::best ||
                               (settings.surface_choice == SurfaceChoice::separable && m == SurfaceModel::separable) ||
                               (settings.surface_choice == SurfaceChoice::bivariate && m == SurfaceModel::bivariate) ||
                               (settings.surface_choice == SurfaceChoice::trivariate && m == SurfaceModel::trivariate);
          if (!allowed) continue;
          for (int ci = 0; ci < static_cast<int>(surface_tables[ti].candidates.size()); ++ci) {
            pool.push_back(surface_tables[ti].candidates[ci]);
            origin.push_back({ti, ci});
          }
        }
        CvTable pooled;
        pooled.candidates = pool;
        const int pick = select_candidate(scores_of(pool), complexities(pool, true), opt.selection, floor);
        crep.surface_choice = chosen_from(pooled, pick, what2);
        surface_tables[origin[pick].first].chosen = origin[pick].second;
        cm.surface = pool[pick].surface;
      } else {
        cm.surface = *cfix.surface;
        crep.surface_choice = from_config();
      }
      for (auto& t : surface_tables) result.cv_tables.push_back(std::move(t));

      if (cm.surface.model == SurfaceModel::zero) {
        cm.parameter_order = 0;
        cm.beta = Eigen::MatrixXd::Zero(0, 1);
        crep.parameter_choice = from_config();
        continue;
      }
      const Eigen::MatrixXd coefficients = fit_surfaces(cm.surface, model.frame, xy, values, opt,
                                                        what2 + " " + cm.surface.label(), &crep.surface_fit);

      // ---- relation 3 (002 eqs. 45–46) ----
      const std::string what3 = name(d, c, "relation 3 (surface coefficients)");
      const Eigen::MatrixXd S = surface_design(cm.surface, model.frame, xy);
      CvTable parameter_table;
      parameter_table.relation = Relation::parameters;
      parameter_table.direction = d;
      parameter_table.component = c;
      parameter_table.model = cm.surface.model;
      parameter_table.exact_floor_mse = floor;
      const int parameter_order = choose_order(
          std::move(parameter_table), lim.parameter, cfix.parameter_order, cv_every_model, opt.selection, what3,
          [&](int k) { return cv_parameter_relation(delta, dm.delta_scale, coefficients, S, k, opt); },
          crep.parameter_choice, result.cv_tables);
      cm.parameter_order = parameter_order;
      cm.beta = fit_parameter_relation(delta, dm.delta_scale, coefficients, parameter_order, opt,
                                       what3 + ", order " + std::to_string(parameter_order), &crep.parameter_fit);
    }
  }
  return result;
}

}  // namespace softsim::fit
