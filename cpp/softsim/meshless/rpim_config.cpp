#include "softsim/meshless/rpim_config.hpp"

#include <cmath>

namespace softsim::meshless {

namespace {

// An integer member within [lo, hi] (checked before narrowing to int).
int read_int(const io::JsonReader& r, const std::string& key, int fallback, int lo, int hi, const std::string& what) {
  if (!r.has(key)) return fallback;
  const std::int64_t v = r.get_int(key);
  r.require(v >= lo && v <= hi, key, what);
  return static_cast<int>(v);
}

std::array<int, 3> read_int3(const io::JsonReader& r, const std::string& key, std::array<int, 3> fallback,
                             int lo, int hi, const std::string& what) {
  if (!r.has(key)) return fallback;
  const auto v = r.get_ints(key);
  r.require(v.size() == 3, key, "[nx, ny, nz]");
  std::array<int, 3> out{};
  for (int a = 0; a < 3; ++a) {
    r.require(v[a] >= lo && v[a] <= hi, key, what);
    out[a] = static_cast<int>(v[a]);
  }
  return out;
}

// {"length": metres} or {"spacing_factor": multiple of the mean nodal spacing}.
LengthSpec read_length(const io::JsonReader& parent, const std::string& key, const LengthSpec& fallback) {
  if (!parent.has(key)) return fallback;
  const io::JsonReader r = parent.at(key);
  if (!r.raw().is_object()) r.fail("{\"length\": metres} or {\"spacing_factor\": factor}");
  LengthSpec out;
  if (r.has("length") == r.has("spacing_factor"))
    r.fail("exactly one of \"length\" (m) or \"spacing_factor\"");
  if (r.has("length")) {
    out.kind = LengthSpec::Kind::absolute;
    out.value = r.get_positive("length");
  } else {
    out.kind = LengthSpec::Kind::spacing_factor;
    out.value = r.get_positive("spacing_factor");
  }
  r.reject_unknown();
  return out;
}

const char* polynomial_name(PolynomialBasis p) { return p == PolynomialBasis::linear ? "linear" : "none"; }

const char* penalty_kind_name(PenaltyParams::Kind k) {
  return k == PenaltyParams::Kind::scale_block ? "scale_block" : "add_diagonal";
}

nlohmann::json length_json(const LengthSpec& l) {
  return l.kind == LengthSpec::Kind::absolute ? nlohmann::json{{"length", l.value}}
                                              : nlohmann::json{{"spacing_factor", l.value}};
}

}  // namespace

PlateScene read_plate_scene(const std::optional<io::JsonReader>& block) {
  PlateScene s;
  if (!block) return s;
  const io::JsonReader& r = *block;
  if (r.has("size")) {
    const auto v = r.get_doubles("size", 3);
    for (int a = 0; a < 3; ++a) r.require(v[a] > 0, "size", "three positive edge lengths (m)");
    s.size = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  s.nodes = read_int3(r, "nodes", s.nodes, 2, 201, "node counts between 2 and 201 per axis");
  r.require(s.nodes[0] % 2 == 1 && s.nodes[1] % 2 == 1, "nodes",
            "odd node counts in x and y (the loaded node is the centre of the top face)");
  s.youngs_modulus = r.get_positive("youngs_modulus", s.youngs_modulus);
  s.poisson_ratio = r.get_double("poisson_ratio", s.poisson_ratio);
  r.require(s.poisson_ratio > -1.0 && s.poisson_ratio < 0.5, "poisson_ratio", "a Poisson ratio in (-1, 0.5)");
  const std::string sup = r.get_choice("supports", {"side_faces", "bottom_edges", "vertical_corner_edges"},
                                       supports_name(s.supports));
  s.supports = sup == "side_faces"     ? PlateSupports::side_faces
               : sup == "bottom_edges" ? PlateSupports::bottom_edges
                                       : PlateSupports::vertical_corner_edges;
  s.background_cells = read_int3(r, "background_cells", s.background_cells, 1, 400, "cell counts between 1 and 400");
  s.gauss_order = read_int(r, "gauss_order", s.gauss_order, 1, 10, "an integer between 1 and 10");
  const double node_count = static_cast<double>(s.nodes[0]) * s.nodes[1] * s.nodes[2];
  r.require(node_count <= 2e5, "nodes", "at most 200000 nodes in all");
  // Every length of the model is measured in the mean spacing: positive edges whose product
  // underflows (or overflows) would leave none.
  const double h = plate_mean_spacing(s);
  r.require(h > 0 && std::isfinite(h), "size",
            "edge lengths whose mean nodal spacing (volume / nodes)^(1/3) is positive and finite");
  const double points = static_cast<double>(s.background_cells[0]) * s.background_cells[1] *
                        s.background_cells[2] * std::pow(s.gauss_order, 3);
  r.require(points <= 1e7, "background_cells", "at most 1e7 Gauss points in all (cells × gauss_order³)");
  if (r.has("body_force")) {
    const auto b = r.get_doubles("body_force", 3);
    s.body_force = Eigen::Vector3d(b[0], b[1], b[2]);
  }
  r.reject_unknown();
  return s;
}

RpimSettings read_rpim_settings(const std::optional<io::JsonReader>& rpim, const std::optional<io::JsonReader>& penalty,
                                const std::optional<io::JsonReader>& solver) {
  RpimSettings s;
  if (rpim) {
    const io::JsonReader& r = *rpim;
    s.alpha_c = r.get_positive("alpha_c", s.alpha_c);
    s.q = r.get_positive("q", s.q);
    r.require(s.q <= 10, "q", "an exponent in (0, 10]");
    s.d_c = read_length(r, "d_c", s.d_c);
    const std::string poly = r.get_choice("polynomial", {"none", "linear"}, polynomial_name(s.polynomial));
    s.polynomial = poly == "linear" ? PolynomialBasis::linear : PolynomialBasis::none;
    s.max_moment_condition = r.get_positive("max_moment_condition", s.max_moment_condition);
    s.max_partition_error = r.get_positive("max_partition_error", s.max_partition_error);
    if (r.has("support")) {
      const io::JsonReader sup = r.at("support");
      const std::string kind = sup.get_choice("kind", {"radius", "nearest"});
      if (kind == "radius") {
        s.support = SupportRule::Kind::radius;
        if (sup.has("radius") == sup.has("spacing_factor"))
          sup.fail("exactly one of \"radius\" (m) or \"spacing_factor\" for a radius support");
        if (sup.has("radius")) s.support_radius = {LengthSpec::Kind::absolute, sup.get_positive("radius")};
        else s.support_radius = {LengthSpec::Kind::spacing_factor, sup.get_positive("spacing_factor")};
      } else {
        s.support = SupportRule::Kind::nearest;
        sup.require(sup.has("count"), "count", "the number of nearest nodes");
        s.support_count = read_int(sup, "count", 0, 1, 1000, "a node count between 1 and 1000");
      }
      sup.reject_unknown();
    }
    r.reject_unknown();
  }
  if (penalty) {
    const io::JsonReader& r = *penalty;
    const std::string kind = r.get_choice("kind", {"scale_block", "add_diagonal"}, penalty_kind_name(s.penalty.kind));
    s.penalty.kind = kind == "add_diagonal" ? PenaltyParams::Kind::add_diagonal : PenaltyParams::Kind::scale_block;
    s.penalty.lambda = r.get_positive("lambda", s.penalty.lambda);
    r.require(s.penalty.lambda >= 1e3 && s.penalty.lambda <= 1e14, "lambda", "a penalty factor between 1e3 and 1e14");
    r.reject_unknown();
  }
  if (solver) {
    if (!solver->raw().is_string()) solver->fail("\"sparse_ldlt\" or \"dense_llt\"");
    const std::string v = solver->as_string();
    if (v != "sparse_ldlt" && v != "dense_llt") solver->fail("\"sparse_ldlt\" or \"dense_llt\"");
    s.solver = v == "dense_llt" ? SolverKind::dense_llt : SolverKind::sparse_ldlt;
  }
  return s;
}

DatasetSpec read_dataset_spec(const io::JsonReader& r) {
  DatasetSpec d;
  const std::string kind = r.get_choice("kind", {"axis_x", "axis_y", "axis_z", "random", "check"});
  d.kind = kind == "axis_x"   ? DatasetKind::axis_x
           : kind == "axis_y" ? DatasetKind::axis_y
           : kind == "axis_z" ? DatasetKind::axis_z
           : kind == "random" ? DatasetKind::random
                              : DatasetKind::check;
  d.max_force = r.get_positive("max_force", d.max_force);
  if (d.kind == DatasetKind::check) {
    if (r.has("force")) {
      const auto f = r.get_doubles("force", 3);
      d.force = Eigen::Vector3d(f[0], f[1], f[2]);
    }
  } else if (d.kind == DatasetKind::random) {
    d.count = read_int(r, "count", DatasetSpec::kRandomCount, 1, 100000, "a case count between 1 and 100000");
    const std::int64_t seed = r.get_int("seed", static_cast<std::int64_t>(d.seed));
    r.require(seed >= 0, "seed", "a non-negative integer");
    d.seed = static_cast<std::uint64_t>(seed);
  } else {
    if (r.has("magnitudes")) {
      r.require(!r.has("count"), "count", "either \"count\" or \"magnitudes\", not both");
      d.magnitudes = r.get_doubles("magnitudes");
      r.require(!d.magnitudes.empty() && d.magnitudes.size() <= 100000, "magnitudes",
                "a list of 1 to 100000 force magnitudes (N)");
      d.count = static_cast<int>(d.magnitudes.size());
    } else {
      d.count = read_int(r, "count", d.count, 1, 100000, "a case count between 1 and 100000");
    }
  }
  r.reject_unknown();
  return d;
}

DatasetOutput read_dataset_output(const std::optional<io::JsonReader>& block) {
  DatasetOutput out;
  if (!block) return out;
  out.all_nodes = block->get_bool("all_nodes", out.all_nodes);
  out.stiffness_conditioning = block->get_bool("stiffness_conditioning", out.stiffness_conditioning);
  block->reject_unknown();
  return out;
}

BlockStudy read_block_study(const std::optional<io::JsonReader>& block) {
  BlockStudy b;
  if (!block) return b;
  const io::JsonReader& r = *block;
  const std::string field = r.get_choice("field", {"plane_wave", "linear_patch"},
                                         b.field == ManufacturedField::linear_patch ? "linear_patch" : "plane_wave");
  b.field = field == "linear_patch" ? ManufacturedField::linear_patch : ManufacturedField::plane_wave;
  b.edge = r.get_positive("edge", b.edge);
  b.youngs_modulus = r.get_positive("youngs_modulus", b.youngs_modulus);
  b.poisson_ratio = r.get_double("poisson_ratio", b.poisson_ratio);
  r.require(b.poisson_ratio > -1.0 && b.poisson_ratio < 0.5, "poisson_ratio", "a Poisson ratio in (-1, 0.5)");
  b.gauss_order = read_int(r, "gauss_order", b.gauss_order, 1, 10, "an integer between 1 and 10");
  r.reject_unknown();
  return b;
}

IndentationInputs read_indentation(const io::JsonReader& r) {
  IndentationInputs in;
  in.force = r.get_positive("force");
  in.depth = r.get_positive("depth");
  in.probe_radius = r.get_positive("probe_radius");
  in.poisson_ratio = r.get_double("poisson_ratio");
  r.require(in.poisson_ratio > -1.0 && in.poisson_ratio < 0.5, "poisson_ratio", "a Poisson ratio in (-1, 0.5)");
  r.reject_unknown();
  return in;
}

nlohmann::json plate_scene_json(const PlateScene& s) {
  return {{"size", {s.size.x(), s.size.y(), s.size.z()}},
          {"nodes", s.nodes},
          {"node_order", "i + nx (j + ny k), node (i, j, k) at (i hx, j hy, k hz)"},
          {"youngs_modulus", s.youngs_modulus},
          {"poisson_ratio", s.poisson_ratio},
          {"supports", supports_name(s.supports)},
          {"background_cells", s.background_cells},
          {"gauss_order", s.gauss_order},
          {"body_force", {s.body_force.x(), s.body_force.y(), s.body_force.z()}}};
}

nlohmann::json rpim_settings_json(const RpimSettings& s, const RbfParams& rbf, const SupportRule& support,
                                  double mean_spacing) {
  nlohmann::json sup = support.kind == SupportRule::Kind::radius
                           ? nlohmann::json{{"kind", "radius"}, {"radius", support.radius},
                                            {"requested", length_json(s.support_radius)}}
                           : nlohmann::json{{"kind", "nearest"}, {"count", support.count}};
  return {{"alpha_c", s.alpha_c},
          {"q", s.q},
          {"d_c", rbf.d_c},
          {"d_c_requested", length_json(s.d_c)},
          {"shape_length", rbf.shape_length()},
          {"polynomial", polynomial_name(s.polynomial)},
          {"max_moment_condition", s.max_moment_condition},
          {"max_partition_error", s.max_partition_error},
          {"support", sup},
          {"mean_spacing", mean_spacing},
          {"penalty", {{"kind", penalty_kind_name(s.penalty.kind)},
                       {"lambda", s.penalty.lambda}}},
          {"solver", solver_name(s.solver)}};
}

}  // namespace softsim::meshless
