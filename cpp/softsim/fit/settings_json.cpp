#include "softsim/fit/settings_json.hpp"

namespace softsim::fit {

namespace {

int read_order(const io::JsonReader& node, const std::string& key, int fallback) {
  const std::int64_t v = node.get_int(key, fallback);
  node.require(v >= 0 && v <= kMaxOrder, key, "an order between 0 and " + std::to_string(kMaxOrder));
  return static_cast<int>(v);
}

int as_order(const io::JsonReader& node) {
  const std::int64_t v = node.as_int();
  if (v < 0 || v > kMaxOrder) node.fail("an order between 0 and " + std::to_string(kMaxOrder));
  return static_cast<int>(v);
}

void read_cv(const io::JsonReader& cv, FitSettings& s) {
  const std::int64_t folds = cv.get_int("folds", s.options.folds);
  cv.require(folds == 0 || folds >= 2, "folds", "0 (leave-one-out) or at least 2 folds");
  s.options.folds = static_cast<int>(folds);
  const std::int64_t seed = cv.get_int("seed", static_cast<std::int64_t>(s.options.seed));
  cv.require(seed >= 0, "seed", "a non-negative integer");
  s.options.seed = static_cast<std::uint64_t>(seed);
  s.options.selection = cv.get_choice("selection", {"one_se", "min"}, to_string(s.options.selection)) == "min"
                            ? Selection::min_error
                            : Selection::one_standard_error;
  s.options.exact_relative = cv.get_double("exact_relative", s.options.exact_relative);
  cv.require(s.options.exact_relative >= 0.0 && s.options.exact_relative < 1.0, "exact_relative",
             "a number in [0, 1)");
  if (const auto mo = cv.optional("max_orders")) {
    s.limits.force = read_order(*mo, "force", s.limits.force);
    if (mo->has("surface")) {
      const io::JsonReader ab = mo->at("surface");
      if (!ab.raw().is_array() || ab.raw().size() != 2) ab.fail("[max a, max b]");
      s.limits.surface_x = as_order(ab[0]);
      s.limits.surface_y = as_order(ab[1]);
    }
    s.limits.bivariate = read_order(*mo, "bivariate", s.limits.bivariate);
    s.limits.trivariate = read_order(*mo, "trivariate", s.limits.trivariate);
    s.limits.parameter = read_order(*mo, "parameters", s.limits.parameter);
    mo->reject_unknown();
  }
  cv.reject_unknown();
}

void read_solver(const io::JsonReader& sv, LmSettings& lm) {
  const std::int64_t it = sv.get_int("max_iterations", lm.max_iterations);
  sv.require(it >= 1 && it <= 100000, "max_iterations", "an iteration limit between 1 and 100000");
  lm.max_iterations = static_cast<int>(it);
  lm.function_tolerance = sv.get_positive("function_tolerance", lm.function_tolerance);
  lm.gradient_tolerance = sv.get_positive("gradient_tolerance", lm.gradient_tolerance);
  lm.parameter_tolerance = sv.get_positive("parameter_tolerance", lm.parameter_tolerance);
  lm.initial_damping = sv.get_positive("initial_damping", lm.initial_damping);
  lm.max_condition = sv.get_positive("max_condition", lm.max_condition);
  sv.reject_unknown();
}

void read_orders(const io::JsonReader& orders, FitSettings& s) {
  for (int d = 0; d < 3; ++d) {
    const auto dir = orders.optional(kAxis[d]);
    if (!dir) continue;
    DirectionOrders& fixed = s.fixed[d];
    if (dir->has("force")) fixed.force_order = read_order(*dir, "force", 0);
    if (const auto comps = dir->optional("components")) {
      for (int c = 0; c < 3; ++c) {
        const auto comp = comps->optional(kAxis[c]);
        if (!comp) continue;
        if (comp->has("surface")) fixed.components[c].surface = surface_terms_from_json(comp->at("surface"));
        if (comp->has("parameters")) fixed.components[c].parameter_order = read_order(*comp, "parameters", 0);
        comp->reject_unknown();
      }
      comps->reject_unknown();
    }
    dir->reject_unknown();
  }
  orders.reject_unknown();
}

}  // namespace

SurfaceTerms surface_terms_from_json(const io::JsonReader& node) {
  const std::string model = node.get_choice("model", {"separable", "bivariate", "trivariate", "zero"});
  SurfaceTerms terms;
  if (model == "separable") {
    const io::JsonReader ab = node.at("orders");
    if (!ab.raw().is_array() || ab.raw().size() != 2) ab.fail("[a, b]");
    terms = SurfaceTerms::separable(as_order(ab[0]), as_order(ab[1]));
  } else if (model == "bivariate") {
    terms = SurfaceTerms::bivariate(as_order(node.at("degree")));
  } else if (model == "trivariate") {
    const int degree = as_order(node.at("degree"));
    int z_degree = degree;
    if (node.has("z_degree")) {
      const io::JsonReader zd = node.at("z_degree");
      z_degree = as_order(zd);
      if (z_degree > degree) zd.fail("a z degree between 0 and the degree " + std::to_string(degree));
    }
    terms = SurfaceTerms::trivariate(degree, z_degree);
  } else {
    terms = SurfaceTerms::zero();
  }
  node.reject_unknown();
  return terms;
}

nlohmann::json surface_terms_to_json(const SurfaceTerms& terms) {
  switch (terms.model) {
    case SurfaceModel::separable:
      return {{"model", "separable"}, {"orders", {terms.order_x, terms.order_y}}};
    case SurfaceModel::bivariate: return {{"model", "bivariate"}, {"degree", terms.degree}};
    case SurfaceModel::trivariate:
      return {{"model", "trivariate"}, {"degree", terms.degree}, {"z_degree", terms.z_degree}};
    case SurfaceModel::zero: break;
  }
  return {{"model", "zero"}};
}

FitSettings fit_settings_from_json(const io::JsonReader& config) {
  FitSettings s;
  s.options.basis = config.get_choice("basis", {"legendre", "monomial"}, to_string(s.options.basis)) == "monomial"
                        ? Basis::monomial
                        : Basis::legendre;
  s.options.scale_inputs =
      config.get_choice("input_scaling", {"unit_interval", "none"}, s.options.scale_inputs ? "unit_interval" : "none") == "unit_interval";
  const std::string model =
      config.get_choice("surface_model", {"separable", "bivariate", "trivariate", "best"}, to_string(s.surface_choice));
  s.surface_choice = model == "separable"    ? SurfaceChoice::separable
                     : model == "bivariate"  ? SurfaceChoice::bivariate
                     : model == "trivariate" ? SurfaceChoice::trivariate
                                             : SurfaceChoice::best;
  s.loaded_node_from_relation1 =
      config.get_choice("loaded_node_displacement", {"relation1", "surface"},
                        s.loaded_node_from_relation1 ? "relation1" : "surface") == "relation1";
  if (const auto cv = config.optional("cv")) read_cv(*cv, s);
  if (const auto sv = config.optional("solver")) read_solver(*sv, s.options.lm);
  if (const auto orders = config.optional("orders")) read_orders(*orders, s);
  return s;
}

nlohmann::json fit_settings_to_json(const FitSettings& s) {
  const LmSettings& lm = s.options.lm;
  nlohmann::json orders = nlohmann::json::object();
  for (int d = 0; d < 3; ++d) {
    const DirectionOrders& f = s.fixed[d];
    nlohmann::json dir = nlohmann::json::object();
    if (f.force_order) dir["force"] = *f.force_order;
    nlohmann::json comps = nlohmann::json::object();
    for (int c = 0; c < 3; ++c) {
      nlohmann::json comp = nlohmann::json::object();
      if (f.components[c].surface) comp["surface"] = surface_terms_to_json(*f.components[c].surface);
      if (f.components[c].parameter_order) comp["parameters"] = *f.components[c].parameter_order;
      if (!comp.empty()) comps[kAxis[c]] = comp;
    }
    if (!comps.empty()) dir["components"] = comps;
    if (!dir.empty()) orders[kAxis[d]] = dir;
  }
  return {{"basis", to_string(s.options.basis)},
          {"input_scaling", s.options.scale_inputs ? "unit_interval" : "none"},
          {"surface_model", to_string(s.surface_choice)},
          {"loaded_node_displacement", s.loaded_node_from_relation1 ? "relation1" : "surface"},
          {"cv",
           {{"folds", s.options.folds},
            {"seed", s.options.seed},
            {"selection", to_string(s.options.selection)},
            {"exact_relative", s.options.exact_relative},
            {"max_orders",
             {{"force", s.limits.force},
              {"surface", {s.limits.surface_x, s.limits.surface_y}},
              {"bivariate", s.limits.bivariate},
              {"trivariate", s.limits.trivariate},
              {"parameters", s.limits.parameter}}}}},
          {"solver",
           {{"max_iterations", lm.max_iterations},
            {"function_tolerance", lm.function_tolerance},
            {"gradient_tolerance", lm.gradient_tolerance},
            {"parameter_tolerance", lm.parameter_tolerance},
            {"initial_damping", lm.initial_damping},
            {"max_condition", lm.max_condition}}},
          {"orders", orders}};
}

}  // namespace softsim::fit
