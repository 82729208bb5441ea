#include "softsim/haptic/haptic_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "softsim/io/errors.hpp"

namespace softsim::haptic {

void HapticRecord::reserve(long n) {
  time.reserve(n);
  probe.reserve(n);
  force.reserve(n);
  contact.reserve(n);
  compute_seconds.reserve(n);
}

void HapticRecord::push(double t, const Eigen::Vector3d& p, const Eigen::Vector3d& f, bool in_contact,
                        double seconds) {
  time.push_back(t);
  probe.push_back(p);
  force.push_back(f);
  contact.push_back(in_contact ? 1 : 0);
  compute_seconds.push_back(seconds);
  ++frames;
}

FrameTimeSummary summarize_frame_times(const std::vector<double>& seconds, double frame_step) {
  FrameTimeSummary s;
  s.frames = static_cast<long>(seconds.size());
  if (seconds.empty()) return s;
  std::vector<double> sorted = seconds;
  std::sort(sorted.begin(), sorted.end());
  auto quantile = [&](double q) { return sorted[static_cast<std::size_t>(q * (sorted.size() - 1) + 0.5)]; };
  s.p50 = quantile(0.5);
  s.p99 = quantile(0.99);
  s.max = sorted.back();
  s.deadline_misses = static_cast<long>(sorted.end() - std::upper_bound(sorted.begin(), sorted.end(), frame_step));
  return s;
}

HapticRecord run_haptic(HapticScene& scene, const ProbePath& path, long frames, ForceLimiter* limiter,
                        const Workspace* workspace) {
  using Clock = std::chrono::steady_clock;
  HapticRecord r;
  r.reserve(frames);
  const double h = scene.options().frame_step;
  if (frames > 0) scene.prepare(path.at(0));
  for (long k = 0; k < frames; ++k) {
    // The tip position of frame k is read at its start (001 §3, step 1).
    const Eigen::Vector3d p = path.at(k * h);
    if (workspace && !workspace->contains(p)) {
      char what[160];
      std::snprintf(what, sizeof what, "input at %.9g s: expected a tip position within %.3g m of the organ's bounding box, got one %.3g m away",
                    k * h, workspace->reach(), workspace->distance(p));
      throw InputError(what);
    }
    const auto t0 = Clock::now();
    Eigen::Vector3d f = scene.frame(p);
    if (limiter) f = limiter->limit(k + 1, f);
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    r.push((k + 1) * h, p, f, scene.in_contact(), seconds);
  }
  if (limiter) r.reports["device_safety"] = limiter->payload();
  return r;
}

namespace {

nlohmann::json rows(const std::vector<Eigen::Vector3d>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& x : v) a.push_back({x.x(), x.y(), x.z()});
  return a;
}

// The linked regions' layout and work (null for the whole model): the current primary region,
// how often it was built, and the secondary updates done and skipped over the run.
nlohmann::json regions_payload(const HapticScene& scene) {
  const regions::RegionTracker* t = scene.regions();
  if (!t) return nullptr;
  const auto& o = scene.options().regions;
  const auto& b = t->builds();
  const regions::RegionStats st = t->totals();
  nlohmann::json region = nullptr;
  if (const auto* r = t->active())
    region = {{"centre_node", r->region().centre},
              {"radius", r->region().radius},
              {"primary_tets", r->region().elements.size()},
              {"primary_nodes", r->region().nodes.size()},
              {"interface_nodes", r->region().interface.size()},
              {"setup_seconds", r->stats().setup_seconds},
              {"secondary_setup_seconds", r->stats().secondary_setup_seconds}};
  const regions::TopologyStats& tc = t->topology_stats();
  // The regions' reaction to cuts: the primary engine's local update against the secondary's
  // factorisation and condensation built anew (000's contrast of explicit and precomputed).
  const nlohmann::json topology = {{"changes", tc.changes},
                                   {"local_updates", tc.local_updates},
                                   {"local_seconds_total", tc.local_seconds},
                                   {"local_seconds_max", tc.local_max_seconds},
                                   {"rebuilds", tc.rebuilds},
                                   {"rebuild_seconds_total", tc.rebuild_seconds},
                                   {"rebuild_seconds_max", tc.rebuild_max_seconds},
                                   {"secondary_seconds_total", tc.secondary_seconds},
                                   {"secondary_seconds_max", tc.secondary_max_seconds},
                                   {"linear_model_seconds_total", tc.linear_seconds},
                                   {"cached_regions_invalidated", tc.invalidated}};
  const char* adaptive[] = {"fixed", "linear", "threshold"};
  return {{"coupling", o.coupling == regions::Coupling::exchange ? "exchange" : "condensed"},
          {"radius", o.radius},
          {"adaptive", {{"kind", adaptive[static_cast<int>(o.adaptive.kind)]},
                        {"max_radius", o.adaptive.max_radius},
                        {"levels", o.adaptive.levels},
                        {"frames_per_level", t->frames_per_level()}}},
          {"secondary_every", o.secondary_every},
          {"interpolate", o.interpolate},
          {"secondary", o.secondary_dynamic ? "implicit" : o.far_field_mass ? "guyan" : "static"},
          {"modes", o.far_field_modes},
          {"precision", o.single_precision ? "single" : "double"},
          {"skip_below", o.skip_below},
          {"primary", region},
          {"builds", b.builds},
          {"switches", b.switches},
          {"build_seconds_total", b.seconds},
          {"build_seconds_max", b.max_seconds},
          {"frames", st.frames},
          {"secondary_updates", st.secondary_updates},
          {"secondary_skipped", st.secondary_skipped},
          {"far_field_recoveries", st.far_field_recoveries},
          {"secondary_seconds_total", st.secondary_seconds},
          {"secondary_seconds_max", st.secondary_max_seconds},
          {"build", o.build_in_background ? "background" : "inline"},
          {"swap_after_frames", o.swap_after_frames},
          {"background", {{"builds", b.background_builds},
                          {"swaps", b.swaps},
                          {"swap_seconds_total", b.swap_seconds},
                          {"swap_seconds_max", b.swap_max_seconds},
                          {"frames_while_building", b.frames_while_building},
                          {"frames_contact_held", scene.live_stats().frames_held},
                          {"frames_contact_unapplied", scene.live_stats().frames_unapplied},
                          {"wait_seconds_total", b.wait_seconds},
                          {"wait_seconds_max", b.wait_max_seconds},
                          {"discarded", b.discarded}}},
          {"tool_covers", b.tool_covers},
          {"late_contacts", b.late_contacts},
          {"topology", topology},
          {"interface_seconds_total", st.interface_seconds}};
}

}  // namespace

nlohmann::json haptic_payload(const HapticConfig& config, const HapticScene& scene, const HapticRecord& record,
                              const std::string& mode) {
  const FrameTimeSummary ft = summarize_frame_times(record.compute_seconds, scene.options().frame_step);
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : scene.events()) events.push_back({{"frame", e.frame}, {"message", e.message}});
  std::vector<int> contact(record.contact.begin(), record.contact.end());
  nlohmann::json cuts = nlohmann::json::array();
  const auto& cut_events = scene.model().cut_events();
  for (std::size_t i = 0; i < cut_events.size(); ++i) {
    const auto& ev = cut_events[i];
    cuts.push_back({{"time", scene.cut_time(i)},
                    {"elements_removed", ev.report.elements.size()},
                    {"pieces", ev.pieces},
                    {"loose_pieces", ev.loose_pieces},
                    {"seconds", ev.search_seconds + ev.report.seconds + ev.separation_seconds + ev.pieces_seconds},
                    {"update_seconds", ev.mode == hybrid::CutMode::separate ? ev.separation_seconds : ev.report.seconds},
                    {"cut_mode", ev.mode == hybrid::CutMode::separate ? "separate" : "remove"},
                    {"faces_opened", ev.faces},
                    {"node_copies", ev.copies.size()}});
  }
  double mean_seconds = 0;
  for (double x : record.compute_seconds) mean_seconds += x;
  if (!record.compute_seconds.empty()) mean_seconds /= double(record.compute_seconds.size());
  nlohmann::json payload = {
      {"mode", mode},
      {"solver", scene.options().use_regions ? "regions" : "whole_model"},
      {"regions", regions_payload(scene)},
      {"model", {{"material", config.model.model}, {"nodes", scene.model().num_nodes()},
                 {"tets", scene.model().mesh().num_tets()}}},
      {"frame_step", scene.options().frame_step},
      {"substeps", scene.substeps()},
      {"dt", scene.dt()},
      {"probe_stiffness", scene.options().probe_stiffness},
      {"contact_mode", scene.options().contact == ContactMode::push   ? "push"
                       : scene.options().contact == ContactMode::tool ? "tool"
                       : scene.options().contact == ContactMode::attach ? "attach"
                                                                      : "grasp"},
      {"frames", record.frames},
      {"time", record.time},
      {"probe", rows(record.probe)},
      {"force", rows(record.force)},
      {"contact", contact},
      {"events", events},
      {"cuts", cuts},
      {"blade", {{"sweeps", scene.blade_stats().sweeps},
                 {"seconds_mean", scene.blade_stats().sweeps ? scene.blade_stats().seconds / scene.blade_stats().sweeps : 0.0},
                 {"seconds_max", scene.blade_stats().max_seconds}}},
      {"timing", {{"frame_seconds_mean", mean_seconds}, {"frame_seconds_p50", ft.p50}, {"frame_seconds_p99", ft.p99}, {"frame_seconds_max", ft.max},
                  {"deadline_misses", ft.deadline_misses}, {"threads", config.model.threads}}},
  };
  for (auto it = record.reports.begin(); it != record.reports.end(); ++it) payload[it.key()] = *it;
  return payload;
}

}  // namespace softsim::haptic
