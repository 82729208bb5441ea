#include "softsim/multirate/run_config.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "softsim/io/errors.hpp"
#include "softsim/multirate/exact_reference.hpp"
#include "softsim/multirate/force_metrics.hpp"
#include "softsim/multirate/run_memory.hpp"
#include "softsim/multirate/stability.hpp"

namespace softsim::multirate {

namespace {

using io::JsonReader;

SolverSpec read_solver(const JsonReader& r, const SolverSpec& fallback) {
  SolverSpec s = fallback;
  // A missing kind keeps the fallback's (the top-level solver's, or implicit at the top).
  const char* inherited = fallback.kind == SolverKind::kStatic     ? "static"
                          : fallback.kind == SolverKind::kImplicit ? "implicit"
                                                                   : "explicit";
  const std::string kind = r.get_choice("kind", {"static", "implicit", "explicit"}, inherited);
  s.kind = kind == "static" ? SolverKind::kStatic : kind == "implicit" ? SolverKind::kImplicit : SolverKind::kExplicit;
  if (r.has("implicit_scheme"))
    s.implicit_scheme = r.get_choice("implicit_scheme", {"newmark", "backward_euler"}) == "newmark"
                            ? ImplicitScheme::kNewmark
                            : ImplicitScheme::kBackwardEuler;
  if (r.has("explicit_variant"))
    s.explicit_variant = r.get_choice("explicit_variant", {"central", "backward_damping"}) == "central"
                             ? ExplicitVariant::kCentral
                             : ExplicitVariant::kBackwardDamping;
  r.reject_unknown();
  return s;
}

void read_model(const JsonReader& m, RunConfig& c) {
  m.get_choice("kind", {"bar"});
  const std::int64_t nodes = m.get_int("nodes");
  m.require(nodes >= 2 && nodes <= 100000, "nodes", "between 2 and 100000 nodes");
  c.bar.nodes = static_cast<int>(nodes);
  c.bar.length = m.get_positive("length");
  c.bar.area = m.get_positive("area");
  c.bar.youngs_modulus = m.get_positive("youngs_modulus");
  c.bar.density = m.get_positive("density");
  const JsonReader d = m.at("damping");
  const bool ratio = d.has("ratio"), alpha = d.has("alpha");
  if (ratio == alpha) d.fail("exactly one of \"ratio\" (of the lowest mode) or \"alpha\" (1/s)");
  c.damping.by_ratio = ratio;
  c.damping.value = ratio ? d.get_double("ratio") : d.get_double("alpha");
  d.require(c.damping.value >= 0, ratio ? "ratio" : "alpha", "a number >= 0");
  d.reject_unknown();
  m.reject_unknown();
  // Each value may be fine alone while E A / h or rho A h / 2 overflows or underflows.
  const double k = bar_element_stiffness(c.bar), half_mass = 0.5 * bar_element_mass(c.bar);
  if (!(k > 0 && std::isfinite(k) && half_mass > 0 && std::isfinite(half_mass)))
    m.fail("a bar whose element stiffness E A / h and node mass rho A h / 2 are positive finite numbers");
}

void read_input(const JsonReader& in, double duration, ProbeSignal& s) {
  const std::string kind = in.get_choice("kind", {"chirp", "step", "ramp_hold", "growing_sine"});
  s.amplitude = in.get_double("amplitude");
  in.require(s.amplitude != 0.0 && std::abs(s.amplitude) < 1.0, "amplitude", "a non-zero probe displacement below 1 m");
  if (kind == "chirp") {
    s.kind = ProbeSignal::Kind::kChirp;
    s.start_frequency = in.get_double("start_frequency", 0.0);
    in.require(s.start_frequency >= 0, "start_frequency", "a frequency >= 0 Hz");
    s.end_frequency = in.get_double("end_frequency");
    in.require(s.end_frequency >= 0, "end_frequency", "a frequency >= 0 Hz");
    s.sweep_time = in.get_positive("sweep_time", duration);
  } else if (kind == "step") {
    s.kind = ProbeSignal::Kind::kStep;
    s.start_time = in.get_double("start_time", 0.0);
    in.require(s.start_time >= 0, "start_time", "a time >= 0 s");
  } else if (kind == "ramp_hold") {
    s.kind = ProbeSignal::Kind::kRampHold;
    s.start_time = in.get_double("start_time", 0.0);
    in.require(s.start_time >= 0, "start_time", "a time >= 0 s");
    s.ramp_time = in.get_positive("ramp_time");
  } else {
    s.kind = ProbeSignal::Kind::kGrowingSine;
    s.start_frequency = in.get_positive("frequency");
    s.sweep_time = in.get_positive("growth_time", duration);
  }
  in.reject_unknown();
}

void read_async(const JsonReader& a, const SolverSpec& solver, int free_nodes, double frame_step, double element_length,
                AsyncRegionsSpec& spec) {
  spec.primary_solver = a.has("primary_solver") ? read_solver(a.at("primary_solver"), solver) : solver;
  spec.interpolate = a.get_bool("interpolate", true);
  spec.merge_full_rate = a.get_bool("merge_full_rate", true);
  const JsonReader p = a.at("primary");
  const std::string policy = p.get_choice("policy", {"fixed", "linear", "threshold"}, "fixed");
  PrimarySizePolicy& pol = spec.primary;
  if (policy == "fixed") {
    pol.kind = PrimarySizePolicy::Kind::kFixed;
    const std::int64_t n = p.get_int("nodes");
    p.require(n >= 1 && n <= free_nodes, "nodes", "between 1 and " + std::to_string(free_nodes) + " (the free nodes)");
    pol.min_nodes = pol.max_nodes = static_cast<int>(n);
  } else {
    pol.kind = policy == "linear" ? PrimarySizePolicy::Kind::kLinear : PrimarySizePolicy::Kind::kThreshold;
    const std::int64_t lo = p.get_int("min_nodes");
    p.require(lo >= 1 && lo <= free_nodes, "min_nodes", "between 1 and " + std::to_string(free_nodes));
    const std::int64_t hi = p.get_int("max_nodes");
    p.require(hi >= lo && hi < free_nodes, "max_nodes", "between min_nodes and " + std::to_string(free_nodes - 1) +
                                                            " (the first secondary region keeps at least one node)");
    pol.min_nodes = static_cast<int>(lo);
    pol.max_nodes = static_cast<int>(hi);
    const double hold = p.get_double("hold_time", 0.0);
    p.require(hold >= 0 && hold <= 100 && hold / frame_step <= 1e7, "hold_time",
              "a time between 0 and 100 s and at most 1e7 frames");
    pol.hold_frames = static_cast<int>(std::llround(hold / frame_step));
    if (pol.kind == PrimarySizePolicy::Kind::kLinear) {
      pol.gradient = p.get_positive("gradient");
      pol.scale = p.has("scale") ? p.get_positive("scale") : element_length;  // default: the element length
    } else {
      pol.threshold = p.get_positive("threshold");
    }
  }
  p.reject_unknown();

  const JsonReader list = a.at("secondary");
  RegionBorders borders(free_nodes, spec.primary.max_nodes);
  for (std::size_t r = 0; r < list.size(); ++r) {
    const JsonReader s = list[r];
    SecondaryRegionSpec region;
    // Range checks on the 64-bit value before narrowing (2^32 + 10 must not become 10).
    const std::int64_t every = s.get_int("every");
    s.require(every >= 1 && every <= 100000, "every", "an update interval of 1 to 100000 frames");
    region.every = static_cast<int>(every);
    const std::int64_t nodes = s.get_int("nodes", 0);
    const bool last = r + 1 == list.size();
    s.require(nodes >= (last ? 0 : 1) && nodes <= free_nodes, "nodes",
              last ? "a node count from 0 (the remaining nodes) to " + std::to_string(free_nodes)
                   : "a node count from 1 to " + std::to_string(free_nodes));
    region.nodes = static_cast<int>(nodes);
    const int size = borders.size_of(region.nodes);
    s.require(borders.fits(size), "nodes",
              "a region that fits: " + std::to_string(borders.remaining()) + " free nodes remain after node " +
                  std::to_string(borders.end()));
    borders.append(size);
    region.solver = s.has("solver") ? read_solver(s.at("solver"), solver) : solver;
    s.reject_unknown();
    spec.secondary.push_back(region);
  }
  if (!borders.complete())
    list.fail("regions covering all " + std::to_string(free_nodes) + " free nodes (they cover " +
              std::to_string(borders.end()) + ")");
  if (spec.secondary.empty()) a.fail_member("secondary", "at least one secondary region");
  a.reject_unknown();
}

}  // namespace

RunConfig read_run_config(const JsonReader& cfg) {
  RunConfig c;
  read_model(cfg.at("model"), c);
  const int free_nodes = c.bar.nodes - 1;

  const JsonReader h = cfg.at("haptics");
  const double rate = h.get_positive("rate", 1000.0);
  const double duration = h.get_positive("duration");
  HapticLoopSpec& loop = c.comparison.loop;
  loop.frame_step = 1.0 / rate;
  const double frames = std::round(duration * rate);  // checked before narrowing (may be inf)
  h.require(frames >= 1 && frames <= 1e7, "duration", "between one frame and 1e7 frames at the haptic rate");
  loop.frames = static_cast<long>(frames);
  loop.probe_stiffness = h.get_positive("probe_stiffness");
  h.reject_unknown();
  loop.direction = Eigen::VectorXd::Ones(1);

  read_input(cfg.at("input"), duration, c.comparison.signal);

  c.comparison.whole_solver = cfg.has("solver") ? read_solver(cfg.at("solver"), SolverSpec{}) : SolverSpec{};
  c.comparison.linear_solver =
      cfg.get_choice("linear_solver", {"sparse", "dense"}, "sparse") == "sparse" ? LinearSolverKind::kSparse
                                                                                : LinearSolverKind::kDense;
  c.comparison.enforce_stability_limit = cfg.get_bool("check_stability", true);
  if (cfg.has("async")) {
    AsyncRegionsSpec a;
    read_async(cfg.at("async"), c.comparison.whole_solver, free_nodes, loop.frame_step, bar_element_length(c.bar), a);
    c.comparison.async = a;
  }
  c.comparison.reference = cfg.get_bool("reference", true);
  if (c.comparison.reference && free_nodes > ExactReference::kMaxDofs)
    cfg.fail_member("reference", "false for a model above " + std::to_string(ExactReference::kMaxDofs) + " DOFs");
  const std::int64_t repeats = cfg.get_int("timing_repeats", 3);
  cfg.require(repeats >= 1 && repeats <= 100, "timing_repeats", "1 to 100");
  c.comparison.timing_repeats = static_cast<int>(repeats);
  const std::int64_t series_every = cfg.get_int("series_every", 0);
  cfg.require(series_every >= 0 && series_every <= 10000000, "series_every",
              "an integer from 0 (no time series) to 1e7");
  c.series_every = static_cast<int>(series_every);
  c.comparison.frequency_bin = cfg.get_positive("frequency_bin", 0.5);
  cfg.require(c.comparison.frequency_bin >= 1e-3 && c.comparison.frequency_bin <= 1e6, "frequency_bin",
              "a bin width from 0.001 Hz to 1e6 Hz");
  // The error-by-frequency tables bin the input's frequency at every frame up to its top value
  // (a frequency linear in time: at the first or the last frame): refused here, before the run,
  // where error_by_frequency would refuse it after.
  const ProbeSignal& signal = c.comparison.signal;
  const bool binned = signal.kind == ProbeSignal::Kind::kChirp || signal.kind == ProbeSignal::Kind::kGrowingSine;
  if (binned && (c.comparison.reference || c.comparison.async)) {
    const double last = static_cast<double>(loop.frames - 1) * loop.frame_step;
    const double top = std::max({0.0, signal.frequency(0.0), signal.frequency(last)});
    if (!(top / c.comparison.frequency_bin <= kMaxFrequencyBins)) {
      std::ostringstream what;
      what << "a bin width giving at most 1e7 bins up to the input's top frequency (" << top << " Hz)";
      cfg.fail_member("frequency_bin", what.str());
    }
  }
  c.comparison.contact_free_node = free_nodes - 1;  // the bar's free end (model node N-1)
  cfg.reject_unknown();
  require_run_resources(c);  // before the model or any record is allocated
  return c;
}

}  // namespace softsim::multirate

namespace softsim::multirate {

namespace {

nlohmann::json solver_json(const SolverSpec& s) { return solver_name(s); }

nlohmann::json error_json(const ForceError& e) {
  return {{"rms", e.rms}, {"peak", e.peak}, {"rms_relative", e.rms_relative}, {"peak_relative", e.peak_relative}};
}

nlohmann::json summary_json(const SignalSummary& s) {
  return {{"peak_force", s.peak_force},
          {"seconds_per_frame", s.seconds_per_frame},
          {"max_second_difference", s.max_second_difference}};
}

nlohmann::json bins_json(const FrequencyBins& b) {
  return {{"frequency", b.frequency}, {"rms_error", b.rms_error}, {"rms_reference", b.rms_reference}};
}

std::string signal_kind(const ProbeSignal& s) {
  switch (s.kind) {
    case ProbeSignal::Kind::kChirp: return "chirp";
    case ProbeSignal::Kind::kStep: return "step";
    case ProbeSignal::Kind::kRampHold: return "ramp_hold";
    case ProbeSignal::Kind::kGrowingSine: return "growing_sine";
  }
  return "unknown";
}

template <typename T>
std::vector<T> every_kth(const std::vector<T>& v, int k) {
  std::vector<T> out;
  for (std::size_t i = 0; i < v.size(); i += static_cast<std::size_t>(k)) out.push_back(v[i]);
  return out;
}

}  // namespace

ReducedSystem build_system(const RunConfig& config, ModelSummary& summary) {
  const LinearModel model = make_bar(config.bar);
  ReducedSystem system = reduce(model);
  const double omega1 = lowest_natural_frequency(system);
  const double alpha = config.damping.by_ratio ? 2.0 * config.damping.value * omega1 : config.damping.value;
  set_mass_proportional_damping(system, alpha);

  const int n = system.num_dofs();
  summary.free_nodes = system.num_free_nodes();
  summary.element_length = bar_element_length(config.bar);
  summary.lowest_frequency = omega1 / (2.0 * 3.141592653589793);
  summary.alpha = alpha;
  summary.omega_max_bound = omega_max_bound(system, 0, n);
  summary.eq4_limit = summary.element_length * std::sqrt(config.bar.density / config.bar.youngs_modulus);
  summary.explicit_limit_central = explicit_step_limit(system, 0, n, ExplicitVariant::kCentral);
  summary.explicit_limit_backward = explicit_step_limit(system, 0, n, ExplicitVariant::kBackwardDamping);
  summary.contact_static_stiffness =
      1.0 / contact_compliance(system, config.comparison.contact_free_node, config.comparison.loop.direction);
  return system;
}

std::string config_pointer(const SettingAtFault& setting) {
  switch (setting.kind) {
    case SettingAtFault::Kind::kWholeSolver: return "/solver";
    case SettingAtFault::Kind::kPrimarySolver: return "/async/primary_solver";
    case SettingAtFault::Kind::kSecondarySolver:
      return "/async/secondary/" + std::to_string(setting.secondary_index) + "/solver";
    case SettingAtFault::Kind::kProbeStiffness: return "/haptics/probe_stiffness";
  }
  return "";
}

ComparisonResult run_configured_comparison(const ReducedSystem& system, const RunConfig& config) {
  try {
    return run_comparison(system, config.comparison);
  } catch (const SetupError& e) {
    throw ConfigInputError(config_pointer(e.setting), e.what());
  }
}

nlohmann::json make_payload(const RunConfig& config, const ModelSummary& model, const ComparisonResult& result) {
  const ComparisonSpec& spec = config.comparison;
  nlohmann::json p;
  p["model"] = {{"kind", "bar"},
                {"nodes", config.bar.nodes},
                {"free_nodes", model.free_nodes},
                {"length", config.bar.length},
                {"area", config.bar.area},
                {"youngs_modulus", config.bar.youngs_modulus},
                {"density", config.bar.density},
                {"element_length", model.element_length},
                {"lowest_frequency", model.lowest_frequency},
                {"alpha", model.alpha},
                {"damping_ratio_lowest_mode", model.alpha / (4.0 * 3.141592653589793 * model.lowest_frequency)},
                {"omega_max_bound", model.omega_max_bound},
                {"eq4_step_limit", model.eq4_limit},
                {"explicit_step_limit_central", model.explicit_limit_central},
                {"explicit_step_limit_backward_damping", model.explicit_limit_backward},
                {"contact_static_stiffness", model.contact_static_stiffness}};
  const ProbeSignal& s = spec.signal;
  p["input"] = {{"kind", signal_kind(s)}, {"amplitude", s.amplitude}};
  if (s.kind == ProbeSignal::Kind::kChirp)
    p["input"].update({{"start_frequency", s.start_frequency}, {"end_frequency", s.end_frequency}, {"sweep_time", s.sweep_time}});
  if (s.kind == ProbeSignal::Kind::kGrowingSine)
    p["input"].update({{"frequency", s.start_frequency}, {"growth_time", s.sweep_time}});
  if (s.kind == ProbeSignal::Kind::kStep || s.kind == ProbeSignal::Kind::kRampHold) p["input"]["start_time"] = s.start_time;
  if (s.kind == ProbeSignal::Kind::kRampHold) p["input"]["ramp_time"] = s.ramp_time;
  p["haptics"] = {{"frame_step", spec.loop.frame_step},
                  {"frames", spec.loop.frames},
                  {"probe_stiffness", spec.loop.probe_stiffness}};

  p["whole"] = summary_json(result.whole_summary);
  p["whole"]["solver"] = solver_json(spec.whole_solver);
  if (spec.reference) p["whole"]["error_vs_exact"] = error_json(result.whole_vs_exact);

  if (spec.async) {
    const AsyncRegionsSpec& a = *spec.async;
    nlohmann::json as = summary_json(result.async_summary);
    as["speed_gain"] = result.whole_summary.seconds_per_frame / result.async_summary.seconds_per_frame;
    as["interpolate"] = a.interpolate;
    as["merge_full_rate"] = a.merge_full_rate;
    as["primary_solver"] = solver_json(a.primary_solver);
    const char* policy = a.primary.kind == PrimarySizePolicy::Kind::kFixed    ? "fixed"
                         : a.primary.kind == PrimarySizePolicy::Kind::kLinear ? "linear"
                                                                              : "threshold";
    as["primary"] = {{"policy", policy}, {"min_nodes", a.primary.min_nodes}, {"max_nodes", a.primary.max_nodes}};
    if (a.primary.kind == PrimarySizePolicy::Kind::kLinear)
      as["primary"].update({{"gradient", a.primary.gradient}, {"scale", a.primary.scale}});
    if (a.primary.kind == PrimarySizePolicy::Kind::kThreshold) as["primary"]["threshold"] = a.primary.threshold;
    if (a.primary.adaptive()) as["primary"]["hold_time"] = a.primary.hold_frames * spec.loop.frame_step;
    as["secondary"] = nlohmann::json::array();
    for (const SecondaryRegionSpec& r : a.secondary)
      as["secondary"].push_back({{"nodes", r.nodes},
                                 {"every", r.every},
                                 {"rate", 1.0 / (r.every * spec.loop.frame_step)},
                                 {"solver", solver_json(r.solver)}});
    as["error_vs_whole"] = error_json(result.async_vs_whole);
    if (spec.reference) as["error_vs_exact"] = error_json(result.async_vs_exact);
    double mean = 0.0;
    int lo = result.async.primary_nodes.front(), hi = lo;
    for (int n : result.async.primary_nodes) {
      mean += n;
      lo = std::min(lo, n);
      hi = std::max(hi, n);
    }
    as["primary_nodes"] = {{"min", lo}, {"max", hi}, {"mean", mean / result.async.primary_nodes.size()}};
    as["blocks"] = result.async_blocks;
    p["async"] = as;
  }
  if (spec.reference) {
    p["exact"] = {{"peak_force", result.exact_summary.peak_force},
                  {"max_second_difference", result.exact_summary.max_second_difference},
                  {"loop_spectral_radius", result.loop_spectral_radius}};
  }
  p["explicit_step_limit_in_use"] = std::isfinite(result.explicit_limit) ? nlohmann::json(result.explicit_limit) : nlohmann::json(nullptr);

  const bool periodic = s.kind == ProbeSignal::Kind::kChirp || s.kind == ProbeSignal::Kind::kGrowingSine;
  if (periodic) {
    nlohmann::json b;
    if (spec.reference) b["whole_vs_exact"] = bins_json(result.whole_vs_exact_bins);
    if (spec.async) b["async_vs_whole"] = bins_json(result.async_vs_whole_bins);
    if (spec.async && spec.reference) b["async_vs_exact"] = bins_json(result.async_vs_exact_bins);
    b["bin_width"] = spec.frequency_bin;
    p["by_frequency"] = b;
  }

  if (config.series_every > 0) {
    const int k = config.series_every;
    std::vector<double> time(result.whole.force.size());
    for (std::size_t n = 0; n < time.size(); ++n) time[n] = static_cast<double>(n) * spec.loop.frame_step;
    nlohmann::json series = {{"every", k},
                             {"time", every_kth(time, k)},
                             {"probe", every_kth(result.whole.probe, k)},
                             {"force_whole", every_kth(result.whole.force, k)},
                             {"contact_whole", every_kth(result.whole.contact, k)}};
    if (spec.async) {
      series["force_async"] = every_kth(result.async.force, k);
      series["contact_async"] = every_kth(result.async.contact, k);
      series["primary_nodes"] = every_kth(result.async.primary_nodes, k);
    }
    if (spec.reference) {
      series["force_exact"] = every_kth(result.exact.force, k);
      series["contact_exact"] = every_kth(result.exact.contact, k);
    }
    if (periodic) series["frequency"] = every_kth(result.frequency, k);
    p["series"] = series;
  }
  return p;
}

}  // namespace softsim::multirate
