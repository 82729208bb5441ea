#include "softsim/fit/model_json.hpp"

#include <cmath>

#include "softsim/fit/dataset_json.hpp"
#include "softsim/fit/settings_json.hpp"
#include "softsim/io/artifact.hpp"

namespace softsim::fit {

namespace {

AffineScale scale_from_json(const io::JsonReader& node) {
  AffineScale s;
  s.center = node.get_double("center");
  s.half_width = node.get_positive("half_width");
  node.reject_unknown();
  return s;
}

nlohmann::json vector_to_json(const Eigen::VectorXd& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

Eigen::VectorXd vector_from_json(const io::JsonReader& node) {
  const std::size_t n = node.size();
  Eigen::VectorXd v(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) v[static_cast<Eigen::Index>(i)] = node[i].as_double();
  return v;
}

}  // namespace

nlohmann::json finite_or_null(double value) {
  if (std::isfinite(value)) return value;
  return nullptr;
}

nlohmann::json scale_to_json(const AffineScale& scale) {
  return {{"center", scale.center}, {"half_width", scale.half_width}};
}

nlohmann::json model_to_json(const FitModel& model) {
  nlohmann::json nodes = nlohmann::json::array();
  for (Eigen::Index j = 0; j < model.nodes.rows(); ++j)
    nodes.push_back({model.nodes(j, 0), model.nodes(j, 1), model.nodes(j, 2)});
  nlohmann::json directions = nlohmann::json::object();
  for (int d = 0; d < 3; ++d) {
    const DirectionModel& dm = model.directions[d];
    if (!dm.present) continue;
    nlohmann::json comps = nlohmann::json::object();
    for (int c = 0; c < 3; ++c) {
      const ComponentModel& cm = dm.components[c];
      nlohmann::json beta = nlohmann::json::array();
      for (Eigen::Index k = 0; k < cm.beta.rows(); ++k) beta.push_back(vector_to_json(cm.beta.row(k).transpose()));
      comps[kAxis[c]] = {{"surface", surface_terms_to_json(cm.surface)},
                         {"parameter_order", cm.parameter_order},
                         {"beta", beta}};
    }
    directions[kAxis[d]] = {{"force_scale", scale_to_json(dm.force_to_loaded.scale)},
                            {"force_coefficients", vector_to_json(dm.force_to_loaded.coefficients)},
                            {"delta_scale", scale_to_json(dm.delta_scale)},
                            {"components", comps}};
  }
  return {{"basis", to_string(model.frame.basis)},
          {"scaled_inputs", model.scaled_inputs},
          {"frame",
           {{"x", scale_to_json(model.frame.x)}, {"y", scale_to_json(model.frame.y)}, {"z", scale_to_json(model.frame.z)}}},
          {"loaded_node", model.loaded_node + 1},
          {"loaded_node_from_relation1", model.loaded_node_from_relation1},
          {"top_nodes", nodes},
          {"directions", directions}};
}

FitModel model_from_json(const io::JsonReader& node) {
  FitModel m;
  m.frame.basis = node.get_choice("basis", {"legendre", "monomial"}) == "monomial" ? Basis::monomial : Basis::legendre;
  m.scaled_inputs = node.at("scaled_inputs").as_bool();
  const io::JsonReader frame = node.at("frame");
  m.frame.x = scale_from_json(frame.at("x"));
  m.frame.y = scale_from_json(frame.at("y"));
  // Fits written before the trivariate surfaces have no z scale; only those surfaces read it,
  // and a model that has one without it is refused below.
  const bool has_z = frame.has("z");
  if (has_z) m.frame.z = scale_from_json(frame.at("z"));
  frame.reject_unknown();
  m.nodes = read_xyz_rows(node.at("top_nodes"));
  const long n = static_cast<long>(m.nodes.rows());
  const std::int64_t loaded = node.get_int("loaded_node");
  node.require(loaded >= 1 && loaded <= n, "loaded_node", "a 1-based node number within top_nodes");
  m.loaded_node = static_cast<int>(loaded - 1);
  m.loaded_node_from_relation1 = node.at("loaded_node_from_relation1").as_bool();
  const io::JsonReader dirs = node.at("directions");
  bool any = false;
  for (int d = 0; d < 3; ++d) {
    const auto dn = dirs.optional(kAxis[d]);
    if (!dn) continue;
    any = true;
    DirectionModel& dm = m.directions[d];
    dm.present = true;
    dm.force_to_loaded.basis = m.frame.basis;
    dm.force_to_loaded.scale = scale_from_json(dn->at("force_scale"));
    dm.force_to_loaded.coefficients = vector_from_json(dn->at("force_coefficients"));
    if (dm.force_to_loaded.coefficients.size() < 1 || dm.force_to_loaded.order() > kMaxOrder)
      dn->at("force_coefficients").fail("1 to " + std::to_string(kMaxOrder + 1) + " coefficients");
    dm.delta_scale = scale_from_json(dn->at("delta_scale"));
    const io::JsonReader comps = dn->at("components");
    for (int c = 0; c < 3; ++c) {
      const io::JsonReader cn = comps.at(kAxis[c]);
      ComponentModel& cm = dm.components[c];
      cm.surface = surface_terms_from_json(cn.at("surface"));
      if (cm.surface.uses_z() && !has_z) frame.fail("a z scale (\"z\": {center, half_width}) for the trivariate surfaces");
      const std::int64_t k = cn.get_int("parameter_order");
      cn.require(k >= 0 && k <= kMaxOrder, "parameter_order", "an order between 0 and " + std::to_string(kMaxOrder));
      cm.parameter_order = static_cast<int>(k);
      const io::JsonReader beta = cn.at("beta");
      if (beta.size() != static_cast<std::size_t>(cm.surface.size()))
        beta.fail("one row per surface term (" + std::to_string(cm.surface.size()) + ")");
      cm.beta.resize(cm.surface.size(), cm.parameter_order + 1);
      for (int t = 0; t < cm.surface.size(); ++t) {
        const Eigen::VectorXd row = vector_from_json(beta[t]);
        if (row.size() != cm.parameter_order + 1)
          beta[t].fail("parameter_order + 1 = " + std::to_string(cm.parameter_order + 1) + " numbers");
        cm.beta.row(t) = row.transpose();
      }
      cn.reject_unknown();
    }
    comps.reject_unknown();
    dn->reject_unknown();
  }
  if (!any) dirs.fail("at least one fitted direction (x, y, z)");
  dirs.reject_unknown();
  node.reject_unknown();
  return m;
}

FitModel read_fit_model(const std::string& path) {
  const io::Artifact artifact = io::Artifact::read(path, kFitSchema, kFitSchemaVersion);
  return model_from_json(artifact.payload().at("model"));
}

}  // namespace softsim::fit
