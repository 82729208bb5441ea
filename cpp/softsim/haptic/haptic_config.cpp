#include "softsim/haptic/haptic_config.hpp"

#include <cmath>
#include <string>

#include "softsim/io/errors.hpp"
#include "softsim/io/limits.hpp"

namespace softsim::haptic {

namespace {

using hybrid::read_vec3;

// Bytes a frame takes in the record and in the artifact's JSON (time, probe, force, contact,
// frame time as values and as text).
constexpr double kBytesPerRecordedFrame = 400;

void read_safety(const io::JsonReader& probe, DeviceSafetyConfig& s) {
  s.max_force = probe.get_positive("max_force", s.max_force);
  probe.require(std::isfinite(s.max_force), "max_force", "a finite force limit (N)");
  s.max_force_step = probe.get_positive("max_force_step", s.max_force_step);
  probe.require(std::isfinite(s.max_force_step), "max_force_step", "a finite change of force per frame (N)");
  s.max_distance = probe.get_positive("max_distance", s.max_distance);
  probe.require(std::isfinite(s.max_distance), "max_distance", "a finite distance from the organ (m)");
}

Eigen::Vector3d read_unit(const io::JsonReader& r, const std::string& key) {
  const Eigen::Vector3d v = read_vec3(r, key);
  r.require(v.norm() > 0, key, "a non-zero direction [x, y, z]");
  return v.normalized();
}

void read_input(const io::JsonReader& in, const mesh::TetMesh& mesh, HapticConfig& c) {
  ProbePath& p = c.input;
  const std::string kind = in.get_choice("kind", {"press", "slide", "growing_sine", "chirp", "recorded"});
  if (kind == "recorded") {
    p.kind = ProbePath::Kind::recorded;
    c.recorded_path = in.get_string("path");
    in.reject_unknown();
    p.recorded = read_recorded_path(c.recorded_path);
    return;
  }
  // The tip starts on the surface point nearest to "start", moving along "direction".
  const ContactSurface surface(mesh);
  const std::vector<double> rest(3 * static_cast<std::size_t>(mesh.num_nodes()), 0.0);
  p.origin = surface.closest(read_vec3(in, "start"), rest.data()).position;
  p.direction = read_unit(in, "direction");
  auto& s = p.signal;
  if (kind == "press" || kind == "slide") {
    p.kind = kind == "press" ? ProbePath::Kind::press : ProbePath::Kind::slide;
    s.kind = multirate::ProbeSignal::Kind::kRampHold;
    s.amplitude = in.get_positive("depth");
    s.ramp_time = in.get_positive("ramp_time");
    s.start_time = 0;
    if (kind == "slide") {
      p.slide_direction = read_unit(in, "slide_direction");
      p.slide_speed = in.get_positive("speed");
    }
  } else if (kind == "growing_sine") {  // 001 Fig. 8
    p.kind = ProbePath::Kind::growing_sine;
    s.kind = multirate::ProbeSignal::Kind::kGrowingSine;
    s.amplitude = in.get_positive("amplitude");
    s.start_frequency = in.get_positive("frequency");
    s.sweep_time = in.get_positive("growth_time");
  } else {  // chirp, 001 Fig. 6
    p.kind = ProbePath::Kind::chirp;
    s.kind = multirate::ProbeSignal::Kind::kChirp;
    s.amplitude = in.get_positive("amplitude");
    s.start_frequency = in.get_double("start_frequency", 0.0);
    in.require(s.start_frequency >= 0, "start_frequency", "a frequency >= 0 Hz");
    s.end_frequency = in.get_positive("end_frequency");
    s.sweep_time = in.get_positive("sweep_time");
  }
  in.reject_unknown();
}

void read_realtime(const io::JsonReader& r, RealtimeConfig& rt) {
  const std::string source = r.get_choice("source", {"stdin", "udp"});
  rt.source = source == "udp" ? RealtimeConfig::Source::udp : RealtimeConfig::Source::stdin_lines;
  rt.port = r.get_int32("port", 0);
  r.require(rt.port >= 0 && rt.port <= 65535, "port", "a port number in [0, 65535] (0: any free port)");
  rt.max_frames = r.get_int("max_frames", 0);
  r.require(rt.max_frames >= 0 && rt.max_frames <= 100000000, "max_frames",
            "a frame count in [0, 10^8] (0: until the session ends)");
  io::require_memory(r, "max_frames", kBytesPerRecordedFrame * static_cast<double>(rt.max_frames), "the served frames' record");
  rt.idle_timeout = r.get_double("idle_timeout", rt.idle_timeout);
  r.require(rt.idle_timeout >= 1e-3 && rt.idle_timeout <= 86400, "idle_timeout", "a time in [0.001, 86400] s");
  rt.announce = r.get_bool("announce", rt.announce);
  if (const auto v = r.optional("visual")) {
    rt.visual.path = v->get_string("path");
    v->require(!rt.visual.path.empty(), "path", "a file or named pipe for the surface stream");
    rt.visual.every = v->get_int32("every", rt.visual.every);
    v->require(rt.visual.every >= 1 && rt.visual.every <= 1000000, "every", "a frame count in [1, 10^6]");
    v->reject_unknown();
  }
  r.reject_unknown();
}

}  // namespace

std::string read_haptic_mesh_path(const io::JsonReader& config) { return hybrid::read_mesh_path(config.at("model")); }

HapticConfig read_haptic_config(const io::JsonReader& cfg, const mesh::TetMesh& mesh) {
  HapticConfig c;
  c.model = hybrid::read_dhd_config(cfg.at("model"), mesh);
  if (c.model.static_solver) cfg.at("model").at("solver").fail("an explicit solver (\"kind\": \"explicit\"): a haptic scene steps in time");
  if (c.model.scene.has_probe) cfg.at("model").at("boundary").at("probe").fail("no probe: the haptic scene's probe is the top-level \"probe\"");
  const double rate = cfg.get_positive("frame_rate", 1000.0);
  c.options.frame_step = 1.0 / rate;
  const io::JsonReader probe = cfg.at("probe");
  const std::string contact = probe.get_choice("contact", {"grasp", "attach", "push", "tool"}, "grasp");
  c.options.contact = contact == "push"     ? ContactMode::push
                      : contact == "tool"   ? ContactMode::tool
                      : contact == "attach" ? ContactMode::attach
                                            : ContactMode::grasp;
  if (c.options.contact == ContactMode::tool) {
    // The rigid tool's own contact makes the force: a coupling spring would be a second model of it.
    if (probe.has("stiffness")) probe.fail_member("stiffness", "no stiffness with contact \"tool\" (the rigid tool's contact gives the force)");
    if (probe.has("tool_offset")) c.options.tool_offset = read_vec3(probe, "tool_offset");
    if (c.model.scene.tools.empty())
      probe.fail_member("contact", "\"grasp\", \"attach\" or \"push\", or a model with a rigid tool (model.boundary.tools) for \"tool\"");
  } else {
    c.options.probe_stiffness = probe.get_positive("stiffness");
    c.options.spring_coupling = probe.get_choice("coupling", {"frame", "substep"}, "frame") == "substep"
                                    ? SpringCoupling::substep : SpringCoupling::frame;
  }
  read_safety(probe, c.safety);
  probe.reject_unknown();
  if (const auto blade = cfg.optional("blade")) {
    c.options.blade = true;
    c.options.blade_edge = hybrid::read_vec3(*blade, "edge");
    blade->require(c.options.blade_edge.norm() > 0, "edge", "a blade edge of non-zero length (m)");
    if (blade->get_choice("mode", {"remove", "separate"}, "remove") == "separate") {
      c.options.blade_mode = hybrid::CutMode::separate;
      c.model.separates = true;
    }
    blade->reject_unknown();
  }
  if (const auto r = cfg.optional("regions")) {
    // The regions drive one rigid tool, the probe's (contact "tool"); a second tool, or one the
    // probe does not drive, would move on its own ramp where no region was placed for it.
    const std::size_t tools = c.model.scene.tools.size();
    if (tools > 0 && c.options.contact != ContactMode::tool)
      r->fail("probe.contact \"tool\" with a rigid tool in the model (the regions follow the tool the probe drives)");
    if (tools > 1) r->fail("one rigid tool in the model (the regions follow the tool the probe drives), not " + std::to_string(tools));
    auto& o = c.options.regions;
    c.options.use_regions = true;
    o.radius = r->get_positive("radius");
    o.coupling = r->get_choice("coupling", {"condensed", "exchange"}, "condensed") == "exchange"
                     ? regions::Coupling::exchange : regions::Coupling::condensed;
    o.secondary_every = r->get_int32("secondary_every", o.secondary_every);
    r->require(o.secondary_every >= 1 && o.secondary_every <= 1000000, "secondary_every", "a frame count in [1, 10^6]");
    o.interpolate = r->get_bool("interpolate", o.interpolate);
    const std::string secondary = r->get_choice("secondary", {"static", "implicit", "guyan"}, "static");
    o.secondary_dynamic = secondary == "implicit";
    o.far_field_mass = secondary == "guyan";
    if (o.secondary_dynamic && o.coupling != regions::Coupling::exchange)
      r->fail_member("secondary", "\"static\" or \"guyan\" with the condensed coupling (an implicit-dynamic secondary needs \"exchange\")");
    if (o.far_field_mass && o.coupling != regions::Coupling::condensed)
      r->fail_member("secondary", "\"static\" or \"implicit\" with the exchange coupling (\"guyan\" needs \"condensed\")");
    o.far_field_modes = r->get_int32("modes", 0);
    r->require(o.far_field_modes >= 0 && o.far_field_modes <= 500, "modes", "a mode count in [0, 500]");
    if (o.far_field_modes > 0 && !o.far_field_mass)
      r->fail_member("modes", "0 unless \"secondary\" is \"guyan\" (the modes complete the Guyan far field)");
    o.single_precision = r->get_choice("precision", {"double", "single"}, "double") == "single";
    if (o.single_precision && o.coupling != regions::Coupling::condensed)
      r->fail_member("precision", "\"double\" with the exchange coupling (\"single\" is the condensed interface product)");
    if (o.far_field_mass && !c.model.scene.gravity.isZero())
      r->fail_member("secondary", "no \"guyan\" with gravity (the far field's weight is condensed already)");
    if (r->has("tool_margin")) {
      if (c.options.contact != ContactMode::tool)
        r->fail_member("tool_margin", "no tool_margin without probe.contact \"tool\" (it sizes the region around the tool)");
      c.options.tool_margin = r->get_double("tool_margin");
      r->require(c.options.tool_margin >= 0 && std::isfinite(c.options.tool_margin), "tool_margin",
                 "a distance >= 0 m from the tool's surface");
    }
    // Where a new region is built: in the frame (inline) or beside the frames (background).
    o.build_in_background = r->get_choice("build", {"inline", "background"}, "inline") == "background";
    o.swap_after_frames = r->get_int32("swap_after_frames", o.swap_after_frames);
    r->require(o.swap_after_frames >= -1 && o.swap_after_frames <= 1000000, "swap_after_frames",
               "-1 (swap a region in when it is built) or a frame count in [0, 10^6]");
    o.skip_below = r->get_double("skip_below", o.skip_below);
    r->require(o.skip_below >= 0 && std::isfinite(o.skip_below), "skip_below", "a displacement >= 0 m (0: never skip)");
    if (const auto a = r->optional("adaptive")) {
      auto& ad = o.adaptive;
      ad.kind = a->get_choice("kind", {"linear", "threshold"}) == "linear" ? regions::AdaptiveRadius::Kind::linear
                                                                          : regions::AdaptiveRadius::Kind::threshold;
      ad.max_radius = a->get_positive("max_radius");
      a->require(ad.max_radius > o.radius, "max_radius", "a radius above regions.radius (m)");
      ad.gradient = a->get_double("gradient", ad.gradient);
      a->require(ad.gradient >= 0 && std::isfinite(ad.gradient), "gradient", "m of radius per m of displacement, >= 0");
      ad.threshold = a->get_positive("threshold", ad.threshold);
      ad.levels = a->get_int32("levels", ad.levels);
      a->require(ad.levels >= 2 && ad.levels <= 64, "levels", "a level count in [2, 64]");
      ad.hold_frames = a->get_int32("hold_frames", ad.hold_frames);
      a->require(ad.hold_frames >= 0 && ad.hold_frames <= 1000000, "hold_frames", "a frame count in [0, 10^6]");
      a->reject_unknown();
    }
    r->reject_unknown();
  }
  read_input(cfg.at("input"), mesh, c);
  c.frames = cfg.get_int("frames", c.frames);
  cfg.require(c.frames >= 1 && c.frames <= 100000000, "frames", "a frame count in [1, 10^8]");
  io::require_memory(cfg, "frames", kBytesPerRecordedFrame * static_cast<double>(c.frames), "the frames' record");
  if (const auto rt = cfg.optional("realtime")) read_realtime(*rt, c.realtime);
  cfg.reject_unknown();
  return c;
}

}  // namespace softsim::haptic
