#include "softsim/hybrid/dhd_config.hpp"
#include "softsim/hybrid/tool_config.hpp"
#include "softsim/hybrid/law_config.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>

#include "softsim/dynamics/node_selection.hpp"
#include "softsim/io/artifact.hpp"
#include "softsim/io/limits.hpp"
#include "softsim/io/result_fields.hpp"

namespace softsim::hybrid {

const char* critical_step_name(CriticalStepMethod m) {
  return m == CriticalStepMethod::power_iteration ? "power_iteration" : "altitude";
}

Eigen::Vector3d read_vec3(const io::JsonReader& r, const std::string& key) {
  const auto v = r.get_doubles(key, 3);
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

dynamics::Ramp read_ramp(const io::JsonReader& r) {
  dynamics::Ramp ramp;
  ramp.duration = r.get_double("ramp_time", ramp.duration);
  r.require(ramp.duration >= 0, "ramp_time", "a non-negative time in seconds");
  const bool smooth = ramp.shape == dynamics::Ramp::Shape::smooth;
  ramp.shape = r.get_choice("ramp", {"linear", "smooth"}, smooth ? "smooth" : "linear") == "smooth"
                   ? dynamics::Ramp::Shape::smooth
                   : dynamics::Ramp::Shape::linear;
  return ramp;
}

namespace {

// Exactly one of set / nodes / nearest / sphere / box. `name` describes the selection.
std::vector<int> read_selection(const io::JsonReader& r, const mesh::TetMesh& mesh, std::string& name) {
  static const std::vector<std::string> kSelectors = {"set", "nodes", "nearest", "sphere", "box"};
  int count = 0;
  for (const auto& k : kSelectors) count += r.has(k) ? 1 : 0;
  if (count != 1) r.fail("exactly one node selector of \"set\", \"nodes\", \"nearest\", \"sphere\", \"box\"");
  std::vector<int> nodes;
  if (r.has("set")) {
    name = r.get_string("set");
    const auto it = mesh.node_sets.find(name);
    if (it == mesh.node_sets.end()) {
      std::string known;
      for (const auto& [k, v] : mesh.node_sets) known += (known.empty() ? "" : ", ") + k;
      r.at("set").fail("the name of a node set of the mesh (" + known + ")");
    }
    nodes = it->second;
  } else if (r.has("nodes")) {
    const io::JsonReader list = r.at("nodes");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const auto v = list[i].as_int();
      if (v < 0 || v >= mesh.num_nodes()) list[i].fail("a node index in [0, " + std::to_string(mesh.num_nodes() - 1) + "]");
      nodes.push_back(static_cast<int>(v));
    }
    name = "nodes";
  } else if (r.has("nearest")) {
    nodes.push_back(dynamics::nearest_node(mesh, read_vec3(r, "nearest")));
    name = "node " + std::to_string(nodes.front());
  } else if (r.has("sphere")) {
    const io::JsonReader s = r.at("sphere");
    const Eigen::Vector3d c = read_vec3(s, "center");
    const double radius = s.get_positive("radius");
    s.reject_unknown();
    nodes = dynamics::nodes_in_sphere(mesh, c, radius);
    name = "sphere";
  } else {
    const io::JsonReader b = r.at("box");
    const Eigen::Vector3d lo = read_vec3(b, "min"), hi = read_vec3(b, "max");
    b.reject_unknown();
    nodes = dynamics::nodes_in_box(mesh, lo, hi);
    name = "box";
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  if (nodes.empty()) r.fail("a node selection that matches at least one node");
  return nodes;
}

std::array<bool, 3> read_components(const io::JsonReader& r) {
  std::array<bool, 3> c = {true, true, true};
  if (!r.has("components")) return c;
  const std::string s = r.get_string("components");
  c = {false, false, false};
  bool ok = !s.empty();
  for (char ch : s) {
    const int k = ch == 'x' ? 0 : ch == 'y' ? 1 : ch == 'z' ? 2 : -1;
    if (k < 0 || c[k]) ok = false;
    else c[k] = true;
  }
  if (!ok) r.at("components").fail("a non-empty subset of \"xyz\" without repeats");
  return c;
}

// Ogden's terms: "mu" and "alpha", arrays of one length 1..3, every alpha non-zero (W divides
// by it), sum mu_p alpha_p > 0 (the small-strain shear modulus is half of it), "K" > 0.
material::Ogden read_ogden(const io::JsonReader& m) {
  material::Ogden law;
  const std::vector<double> mu = m.get_doubles("mu");
  m.require(!mu.empty() && mu.size() <= material::Ogden::kMaxTerms, "mu", "an array of 1 to 3 numbers");
  const std::vector<double> alpha = m.get_doubles("alpha");
  m.require(alpha.size() == mu.size(), "alpha", "an array of the same length as mu");
  law.terms = static_cast<int>(mu.size());
  for (int p = 0; p < law.terms; ++p) {
    if (alpha[p] == 0.0) m.at("alpha")[p].fail("a non-zero exponent");
    law.mu[p] = mu[p];
    law.alpha[p] = alpha[p];
  }
  m.require(law.shear_modulus() > 0 && std::isfinite(law.shear_modulus()), "mu",
            "terms with sum mu_p alpha_p > 0 (the shear modulus is half of it)");
  law.bulk = m.get_positive("K");
  return law;
}

// The constitutive law of the TLED and ANP elements (material/hyperelastic.hpp), apart from
// the element formulation the partition chooses: a neo-Hookean form with (E, ν), or
// Mooney–Rivlin with (C10, C01, K), or Ogden with (mu[], alpha[], K), or transversely isotropic
// with (mu, eta, K, fibre; law_config.hpp), whose small-strain (E, ν) the linear and
// corotational elements and the stable step use; "prony" relaxes any of them but the paper's
// neo-Hookean form ("visco_neo_hookean": the decoupled form with (E, ν) and a series).
void read_material(const io::JsonReader& cfg, const mesh::TetMesh& mesh, DhdConfig& c) {
  material::ElasticParameters p;
  // Mooney–Rivlin, Ogden and the fibre law are given by their own moduli, from which (E, ν) follow;
  // the neo-Hookean forms (and the stable law) are given by (E, ν).
  std::optional<material::ElasticLaw> by_moduli;
  std::optional<material::Viscoelastic> prony;  // its base set below
  std::shared_ptr<const std::vector<Eigen::Vector3d>> fibres;
  if (auto m = cfg.optional("material")) {
    c.model_defaulted = !m->has("model");
    c.model = m->get_choice("model",
                             {"neo_hookean_paper", "neo_hookean_decoupled", "mooney_rivlin", "ogden",
                              "stable_neo_hookean", "transversely_isotropic", "visco_neo_hookean", "linear"},
                             c.model);
    // The small-strain (E, ν) a law given by its moduli linearises to, with the density.
    const auto small_strain_of = [&](const auto& law) {
      p.density = m->get_positive("density", p.density);
      p = material::small_strain_parameters(law, p.density);
      m->require(std::isfinite(p.youngs_modulus) && p.youngs_modulus > 0, "K",
                 "moduli whose small-strain Young's modulus 9 K mu / (3 K + mu) is positive and finite");
      by_moduli = law;
    };
    if (c.model == "mooney_rivlin") {
      material::MooneyRivlin mooney_rivlin;
      mooney_rivlin.c10 = m->get_double("C10");
      mooney_rivlin.c01 = m->get_double("C01");
      m->require(mooney_rivlin.c10 + mooney_rivlin.c01 > 0, "C01", "C10 + C01 > 0 (the shear modulus is 2 (C10 + C01))");
      mooney_rivlin.bulk = m->get_positive("K");
      small_strain_of(mooney_rivlin);
    } else if (c.model == "ogden") {
      small_strain_of(read_ogden(*m));
    } else if (c.model == "transversely_isotropic") {
      const material::TransverselyIsotropic transversely_isotropic = read_transversely_isotropic(*m);
      small_strain_of(transversely_isotropic);
      fibres = read_fibre_regions(*m, mesh, transversely_isotropic.fibre);
    } else {
      p.youngs_modulus = m->get_positive("E", p.youngs_modulus);
      p.poisson_ratio = m->get_double("nu", p.poisson_ratio);
      m->require(p.poisson_ratio > -1.0 && p.poisson_ratio < 0.5, "nu", "a Poisson's ratio in (-1, 0.5)");
      p.density = m->get_positive("density", p.density);
    }
    if (m->has("prony")) {
      m->require(c.model != "neo_hookean_paper" && c.model != "linear" && c.model != "stable_neo_hookean", "prony",
                 "no Prony series on this model (it relaxes the isochoric stress of neo_hookean_decoupled, "
                 "visco_neo_hookean, mooney_rivlin, ogden or transversely_isotropic)");
      prony = read_prony(m->at("prony"), material::NeoHookean{});
    } else {
      m->require(c.model != "visco_neo_hookean", "prony", "a Prony series {\"g\": [...], \"tau\": [...]}");
    }
    // A subnormal density (5e-324) or a ratio E/density that overflows gives an infinite wave
    // speed and a zero critical step (000 eq. 34): refused here, where the member is known.
    m->require(p.density >= std::numeric_limits<double>::min() && std::isfinite(std::sqrt(p.youngs_modulus / p.density)),
               "density", "a density whose wave speed sqrt(E / density) is finite");
    m->reject_unknown();
  }
  c.linear_material = c.model == "linear";
  const material::ElasticLaw base =
      by_moduli ? *by_moduli
                : material::ElasticLaw(material::NeoHookean::from(
                      c.model == "neo_hookean_paper" || c.model == "linear" ? material::NeoHookeanForm::paper
                                                                            : material::NeoHookeanForm::decoupled,
                      p));
  if (c.model == "stable_neo_hookean") {  // (E, ν) through Smith et al.'s reparametrisation
    c.material = fem::Material::make(p, material::StableNeoHookean::from(p));
  } else if (prony) {
    prony->base = base;
    c.material = fem::Material::make(p, *prony);
  } else {
    c.material = fem::Material::make(p, std::visit([](const auto& l) -> material::HyperelasticLaw { return l; }, base));
  }
  c.material.fibres = fibres;
}

fem::ElementKind read_kind(const io::JsonReader& r, const std::string& key, const std::vector<std::string>& choices,
                           const std::string& fallback) {
  return *fem::parse_kind(r.get_choice(key, choices, fallback));
}

void read_partition(const io::JsonReader& cfg, const mesh::TetMesh& mesh, DhdConfig& c) {
  PartitionSpec& s = c.partition;
  const std::string default_element = c.linear_material ? "linear" : "tled";
  s.uniform_element = *fem::parse_kind(default_element);
  auto p = cfg.optional("partition");
  if (!p) return;
  const std::string kind = p->get_choice("kind", {"uniform", "layers", "linear_fraction", "tags", "sphere", "strain"},
                                         p->has("linear_fraction") ? "linear_fraction" : "uniform");
  s.linear_element = read_kind(*p, "linear_element", fem::kind_names(true), fem::kind_name(s.linear_element));
  s.nonlinear_element = read_kind(*p, "nonlinear_element", fem::kind_names(false), fem::kind_name(s.nonlinear_element));
  if (kind == "uniform") {
    s.kind = PartitionKind::uniform;
    s.uniform_element = read_kind(*p, "element", fem::kind_names(), default_element);
  } else if (kind == "layers") {
    s.kind = PartitionKind::layers;
    s.nonlinear_layers = p->get_int32("nonlinear_layers");
    p->require(s.nonlinear_layers >= 0, "nonlinear_layers", "a non-negative layer count");
    s.tag = p->get_string("tag", s.tag);
    p->require(mesh.element_tags.count(s.tag) > 0, "tag", "the name of an element tag of the mesh");
  } else if (kind == "linear_fraction") {
    s.kind = PartitionKind::linear_fraction;
    s.linear_fraction = p->get_double("linear_fraction");
    p->require(s.linear_fraction >= 0 && s.linear_fraction <= 1, "linear_fraction", "a share in [0, 1]");
    if (p->has("operating_point")) s.operating_point = read_vec3(*p, "operating_point");
    const bool depth = s.distance == DistanceMetric::depth;
    s.distance = p->get_choice("distance", {"euclidean", "depth"}, depth ? "depth" : "euclidean") == "depth"
                     ? DistanceMetric::depth
                     : DistanceMetric::euclidean;
  } else if (kind == "tags") {
    s.kind = PartitionKind::tags;
    s.tag = p->get_string("tag");
    p->require(mesh.element_tags.count(s.tag) > 0, "tag", "the name of an element tag of the mesh");
    for (auto v : p->get_ints("nonlinear_values")) s.nonlinear_values.push_back(static_cast<int>(v));
  } else if (kind == "sphere") {
    s.kind = PartitionKind::sphere;
    s.center = read_vec3(*p, "center");
    s.radius = p->get_positive("radius");
  } else {
    s.kind = PartitionKind::strain;
    c.strain_reference = p->get_string("reference");
    s.measure = p->get_choice("measure", {"displacement_gradient", "green_lagrange"},
                              s.measure == StrainMeasure::green_lagrange ? "green_lagrange" : "displacement_gradient") ==
                        "green_lagrange"
                    ? StrainMeasure::green_lagrange
                    : StrainMeasure::displacement_gradient;
    const bool has_threshold = p->has("threshold"), has_fraction = p->has("linear_fraction");
    if (has_threshold == has_fraction) p->fail("exactly one of \"threshold\" and \"linear_fraction\"");
    if (has_threshold) {
      s.threshold = p->get_double("threshold");
      p->require(*s.threshold >= 0, "threshold", "a non-negative strain");
    } else {
      s.linear_fraction = p->get_double("linear_fraction");
      p->require(s.linear_fraction >= 0 && s.linear_fraction <= 1, "linear_fraction", "a share in [0, 1]");
    }
    s.reference_displacement =
        io::read_nodal_displacements(io::Artifact::read(c.strain_reference, "dhd_result", 1), mesh.num_nodes());
  }
  p->reject_unknown();
  const bool wants_tled = s.kind != PartitionKind::uniform || s.uniform_element == fem::ElementKind::tled ||
                          fem::volumetric_at_nodes(s.uniform_element);
  if (c.linear_material && wants_tled)
    p->fail("a partition without TLED or ANP elements (material.model is \"linear\"): use {\"kind\": \"uniform\", "
            "\"element\": \"linear\" or \"corotational\"}");
}

void read_boundary(const io::JsonReader& cfg, const mesh::TetMesh& mesh, DhdConfig& c) {
  auto b = cfg.optional("boundary");
  if (!b) return;
  c.has_boundary = true;
  dynamics::Scene& scene = c.scene;
  if (auto fixed = b->optional("fixed")) {
    for (std::size_t i = 0; i < fixed->size(); ++i) {
      const io::JsonReader e = (*fixed)[i];
      dynamics::DisplacementConstraint con;
      if (e.raw().is_string()) {
        con.name = e.as_string();
        const auto it = mesh.node_sets.find(con.name);
        if (it == mesh.node_sets.end()) e.fail("the name of a node set of the mesh");
        con.nodes = it->second;
        if (con.nodes.empty()) e.fail("a non-empty node set");
      } else {
        con.nodes = read_selection(e, mesh, con.name);
        con.components = read_components(e);
        e.reject_unknown();
      }
      con.name = "fixed " + con.name;
      scene.constraints.push_back(con);
    }
  }
  if (auto pres = b->optional("prescribed")) {
    for (std::size_t i = 0; i < pres->size(); ++i) {
      const io::JsonReader e = (*pres)[i];
      dynamics::DisplacementConstraint con;
      con.nodes = read_selection(e, mesh, con.name);
      con.name = "prescribed " + con.name;
      con.displacement = read_vec3(e, "displacement");
      con.components = read_components(e);
      con.ramp = read_ramp(e);
      e.reject_unknown();
      scene.constraints.push_back(con);
    }
  }
  if (auto forces = b->optional("forces")) {
    // Every constraint is read by now (the selections above keep node indices in range).
    const std::vector<char> constrained =
        dynamics::constrained_mask(dynamics::resolve_constraints(scene, mesh.num_nodes()), mesh.num_nodes());
    for (std::size_t i = 0; i < forces->size(); ++i) {
      const io::JsonReader e = (*forces)[i];
      dynamics::NodalLoad load;
      load.nodes = read_selection(e, mesh, load.name);
      load.name = "force " + load.name;
      load.force_per_node = read_vec3(e, "force");
      if (e.get_choice("per", {"node", "total"}, "node") == "total")
        load.force_per_node /= static_cast<double>(load.nodes.size());
      load.ramp = read_ramp(e);
      e.reject_unknown();
      // A force whose every loaded component sits on constrained nodes does nothing but change
      // a reaction: almost surely the wrong node set, so it is refused. (A force on a face whose
      // clamped edge it shares is fine: some of its nodes are free.)
      bool moves_something = false;
      for (int node : load.nodes)
        for (int a = 0; a < 3; ++a)
          if (load.force_per_node[a] != 0.0 && !constrained[3 * node + a]) moves_something = true;
      if (load.force_per_node.isZero(0.0))
        e.fail("a non-zero force (a zero force loads nothing)");
      if (!moves_something)
        e.fail("a force acting on at least one free component, but every loaded node is constrained");
      scene.loads.push_back(load);
    }
  }
  if (b->has("gravity")) {
    // [gx, gy, gz], constant; or {"acceleration": [gx, gy, gz], "ramp_time", "ramp"}, ramped
    // like a force (a dynamic relaxation from zero load, without a force entry per node).
    const io::JsonReader g = b->at("gravity");
    if (g.raw().is_object()) {
      scene.gravity = read_vec3(g, "acceleration");
      scene.gravity_ramp = read_ramp(g);
      g.reject_unknown();
    } else {
      scene.gravity = read_vec3(*b, "gravity");
    }
  }
  if (auto probe = b->optional("probe")) {
    std::string name;
    const std::vector<int> nodes = read_selection(*probe, mesh, name);
    if (nodes.size() != 1) probe->fail("a node selector matching exactly one node");
    scene.has_probe = true;
    scene.probe.node = nodes.front();
    scene.probe.stiffness = probe->get_positive("stiffness");
    scene.probe.displacement = read_vec3(*probe, "displacement");
    scene.probe.ramp = read_ramp(*probe);
    probe->reject_unknown();
  }
  scene.tools = read_tools(*b, mesh);
  b->reject_unknown();
}

void read_solver(const io::JsonReader& cfg, const mesh::TetMesh& mesh, DhdConfig& c) {
  auto s = cfg.optional("solver");
  if (!s) return;
  c.static_solver = s->get_choice("kind", {"explicit", "static"}, c.static_solver ? "static" : "explicit") == "static";
  // Keys of the other solver kind are refused rather than silently ignored.
  const std::set<std::string> explicit_keys = {"steps", "dt", "safety_factor", "force_dt", "energy_interval",
                                               "energy_growth_limit", "dt_check_interval", "contact_search", "critical_step",
                                               "linear_precision"};
  const std::set<std::string> static_keys = {"increments", "max_iterations", "tolerance"};
  for (const auto& key : s->keys())
    if ((c.static_solver && explicit_keys.count(key)) || (!c.static_solver && static_keys.count(key)))
      s->at(key).fail(std::string("no ") + (c.static_solver ? "explicit" : "static") + "-solver key with solver.kind \"" +
                      (c.static_solver ? "static" : "explicit") + "\"");
  ExplicitConfig& e = c.explicit_solver;
  e.steps = s->get_int32("steps", e.steps);
  s->require(e.steps >= 0, "steps", "a non-negative step count");
  // One explicit step updates every element once, and costs about 200 element updates more
  // whatever the mesh (io/limits.hpp: the work limit).
  io::require_work(*s, "steps", static_cast<double>(e.steps) * (static_cast<double>(mesh.tets.size()) + 200.0));
  if (s->has("dt")) e.dt = s->get_positive("dt");
  e.safety_factor = s->get_positive("safety_factor", e.safety_factor);
  s->require(e.safety_factor <= 1.0, "safety_factor", "a factor in (0, 1]");
  e.force_dt = s->get_bool("force_dt", e.force_dt);
  e.dt_check_interval = s->get_int32("dt_check_interval", e.dt_check_interval);
  s->require(e.dt_check_interval >= 0, "dt_check_interval", "a non-negative step count (0: no re-estimate)");
  if (e.dt && s->has("dt_check_interval") && e.dt_check_interval > 0)
    s->at("dt_check_interval").fail("no step re-estimate with a fixed \"dt\" (leave dt out for the automatic step)");
  e.critical_step = s->get_choice("critical_step", {"altitude", "power_iteration"},
                                  critical_step_name(e.critical_step)) == "power_iteration"
                        ? CriticalStepMethod::power_iteration
                        : CriticalStepMethod::altitude;
  e.energy_interval = s->get_int32("energy_interval", e.energy_interval);
  s->require(e.energy_interval >= 1, "energy_interval", "a positive step count");
  e.energy_growth_limit = s->get_positive("energy_growth_limit", e.energy_growth_limit);
  e.contact_search = s->get_choice("contact_search", {"grid", "all"}, "grid") == "grid";
  e.linear_precision = s->get_choice("linear_precision", {"double", "single"},
                                     fem::linear_precision_name(e.linear_precision)) == "single"
                           ? fem::LinearPrecision::single_precision
                           : fem::LinearPrecision::double_precision;
  s->require(e.energy_growth_limit >= 1.0, "energy_growth_limit", "a factor of at least 1");
  dynamics::StaticOptions& st = c.static_options;
  st.increments = s->get_int32("increments", st.increments);
  s->require(st.increments >= 1, "increments", "a positive increment count");
  // An increment is Newton iterations, each an assembly and a sparse factorisation: counted as
  // 100 explicit steps.
  io::require_work(*s, "increments", 100.0 * static_cast<double>(st.increments) * (static_cast<double>(mesh.tets.size()) + 200.0));
  st.max_iterations = s->get_int32("max_iterations", st.max_iterations);
  s->require(st.max_iterations >= 1, "max_iterations", "a positive iteration count");
  st.tolerance = s->get_positive("tolerance", st.tolerance);
  s->reject_unknown();
}

void read_output(const io::JsonReader& cfg, const mesh::TetMesh& mesh, DhdConfig& c) {
  auto o = cfg.optional("output");
  if (!o) return;
  OutputConfig& out = c.output;
  out.vtu = o->get_string("vtu", out.vtu);
  out.vtu_interval = o->get_int32("vtu_interval", out.vtu_interval);
  o->require(out.vtu_interval >= 0, "vtu_interval", "a non-negative step count");
  if (out.vtu_interval > 0 && out.vtu.empty()) o->fail("a \"vtu\" path together with \"vtu_interval\"");
  out.vtu_format = *io::parse_vtu_format(
      o->get_choice("vtu_format", io::kVtuFormatNames, io::vtu_format_name(out.vtu_format)));
  if (o->has("vtu_format") && out.vtu.empty()) o->fail("a \"vtu\" path together with \"vtu_format\"");
  if (auto traj = o->optional("trajectories")) {
    for (std::size_t i = 0; i < traj->size(); ++i) {
      const io::JsonReader e = (*traj)[i];
      if (e.raw().is_number()) {
        const auto v = e.as_int();
        if (v < 0 || v >= mesh.num_nodes()) e.fail("a node index in [0, " + std::to_string(mesh.num_nodes() - 1) + "]");
        out.trajectory_nodes.push_back(static_cast<int>(v));
      } else {
        std::string name;
        for (int n : read_selection(e, mesh, name)) out.trajectory_nodes.push_back(n);
        e.reject_unknown();
      }
    }
  }
  out.trajectory_interval = o->get_int32("trajectory_interval", out.trajectory_interval);
  o->require(out.trajectory_interval >= 1, "trajectory_interval", "a positive step count");
  out.velocity = o->get_bool("velocity", out.velocity);
  out.displacement = o->get_bool("displacement", out.displacement);
  o->reject_unknown();
}

void read_bench(const io::JsonReader& cfg, const mesh::TetMesh& mesh, DhdConfig& c) {
  auto b = cfg.optional("bench");
  if (!b) return;
  c.bench.steps = b->get_int32("steps", c.bench.steps);
  b->require(c.bench.steps >= 1, "steps", "a positive step count");
  c.bench.repeats = b->get_int32("repeats", c.bench.repeats);
  b->require(c.bench.repeats >= 1 && c.bench.repeats <= 1000, "repeats", "between 1 and 1000 repetitions");
  if (b->has("response_set")) {
    const std::string set = b->get_string("response_set");
    const auto it = mesh.node_sets.find(set);
    if (it == mesh.node_sets.end() || it->second.empty()) b->fail_member("response_set", "a non-empty node set of the mesh");
    c.bench.response_nodes = it->second;
  }
  if (b->has("threads")) {
    c.bench.threads.clear();
    for (auto t : b->get_ints("threads")) {
      b->require(t >= 1 && t <= 256, "threads", "thread counts between 1 and 256");
      c.bench.threads.push_back(static_cast<int>(t));
    }
    b->require(!c.bench.threads.empty(), "threads", "at least one thread count");
  }
  if (b->has("linear_fraction")) {
    c.bench.linear_fractions = b->at("linear_fraction").raw().is_array() ? b->get_doubles("linear_fraction")
                                                                          : std::vector<double>{b->get_double("linear_fraction")};
    for (double r : c.bench.linear_fractions)
      b->require(r >= 0 && r <= 1, "linear_fraction", "a share in [0, 1] or a list of them");
  }
  b->reject_unknown();
}

}  // namespace

std::string read_mesh_path(const io::JsonReader& config) { return config.get_input_path("mesh"); }

DhdConfig read_dhd_config(const io::JsonReader& cfg, const mesh::TetMesh& mesh) {
  DhdConfig c;
  c.mesh_path = cfg.get_string("mesh");  // as written (the mesh is loaded by the caller)
  read_material(cfg, mesh, c);
  if (auto d = cfg.optional("damping")) {
    c.damping_alpha = d->get_double("alpha", c.damping_alpha);
    d->require(c.damping_alpha >= 0, "alpha", "a non-negative damping coefficient (1/s)");
    d->reject_unknown();
  }
  read_partition(cfg, mesh, c);
  read_boundary(cfg, mesh, c);
  read_solver(cfg, mesh, c);
  read_output(cfg, mesh, c);
  c.threads = cfg.get_int32("threads", c.threads);
  cfg.require(c.threads >= 1 && c.threads <= 256, "threads", "a thread count between 1 and 256");
  read_bench(cfg, mesh, c);
  c.cuts = read_cuts(cfg, mesh);
  for (const auto& cut : c.cuts) c.separates = c.separates || cut.mode == CutMode::separate;
  if (!c.cuts.empty() && c.static_solver) cfg.fail_member("cuts", "an explicit solver (a cut is an event in time)");
  if (!c.scene.tools.empty() && c.static_solver)
    cfg.at("boundary").fail_member("tools", "an explicit solver (rigid-tool contact is solved by the explicit engine)");
  cfg.reject_unknown();
  return c;
}

}  // namespace softsim::hybrid
