#include "softsim/haptic/view_loop.hpp"

#include <chrono>
#include <cstdio>

#include "softsim/cutting/blade.hpp"
#include "softsim/io/errors.hpp"
#include "softsim/regions/region_solver.hpp"

namespace softsim::haptic {

namespace {
using Clock = std::chrono::steady_clock;
constexpr int kCatchUpFrames = 5;  // a loop further behind the wall clock is set back, not raced
}

ViewLoop::ViewLoop(HapticScene& scene, const Eigen::Vector3d& start, const ViewLoopOptions& options)
    : scene_(scene), options_(options), track_(start, options.latency), previous_tip_(start) {
  // Sized before the frames: a state copy then allocates nothing unless a cut grows the mesh.
  const int n = scene_.model().num_nodes();
  for (int i = 0; i < 3; ++i) {
    ViewState& s = states_.buffer(i);
    s.positions.reserve(3 * static_cast<std::size_t>(n));
    if (scene_.regions()) s.region.reserve(n);
    fill_topology(s.topology);
  }
  nodes_seen_ = n;
  cuts_seen_ = scene_.model().cut_events().size();
  // A bounded session (max_frames) sizes the record once; an open one starts with a minute and
  // grows by doubling (a copy of the record inside one frame, 6 times in an hour at 1 kHz).
  record_.reserve(options_.max_frames > 0 ? options_.max_frames : 60000);
}

ViewLoop::~ViewLoop() { stop(); }

void ViewLoop::start(std::function<void()> on_end) {
  on_end_ = std::move(on_end);
  thread_ = std::thread([this] { run(); });
}

void ViewLoop::stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

bool ViewLoop::push(const PointerSample& s) {
  if (samples_.push(s)) return true;
  dropped_.fetch_add(1, std::memory_order_relaxed);
  return false;
}

void ViewLoop::run() {
  try {
    const double h = scene_.options().frame_step;
    auto start = Clock::now();
    for (long k = 0; !stop_.load(std::memory_order_relaxed) && (options_.max_frames == 0 || k < options_.max_frames);
         ++k) {
      if (options_.paced) {
        // Frame k starts at start + k × frame step on the wall clock; a late frame starts at once
        // (its lateness is reported) and the next ones catch up. A loop more than a few frames
        // behind (the machine was busy) does not race to catch up: its clock is set back, as a
        // device's servo loop just takes its next tick.
        const auto due = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(k * h));
        const auto now = Clock::now();
        if (now < due) {
          std::this_thread::sleep_until(due);
        } else {
          const double late = std::chrono::duration<double>(now - due).count();
          lag_max_ = std::max(lag_max_, late);
          if (late > kCatchUpFrames * h) start += now - due;
        }
      }
      frame(k);
    }
  } catch (...) {
    error_ = std::current_exception();
  }
  if (on_end_) on_end_();
}

void ViewLoop::frame(long k) {
  const double h = scene_.options().frame_step;
  const double now = k * h;
  if (restart_.exchange(false)) track_.restart();
  PointerSample s;
  while (samples_.pop(s)) {
    track_.push(s, now);
    ++samples_seen_;
  }
  const PointerSample& tip = track_.at(now);
  const Eigen::Vector3d p = tip.position;
  const auto t0 = Clock::now();
  if (tip.blade) blade_cut(tip);
  blade_ = tip.blade;
  previous_tip_ = p;
  Eigen::Vector3d f = scene_.frame(p);
  if (options_.limiter) f = options_.limiter->limit(k + 1, f);
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  record_.push((k + 1) * h, p, f, scene_.in_contact(), seconds);
  window_sum_ += seconds;
  window_max_ = std::max(window_max_, seconds);
  ++window_frames_;
  if (seconds > h) ++deadline_misses_;
  if ((k + 1) % options_.state_every == 0) publish(k + 1);
}

void ViewLoop::blade_cut(const PointerSample& s) {
  // Between frames, the elements the blade's edge swept since the previous frame are cut by the
  // scene's own machinery (HapticScene::cut: the model, its contact surface and the regions).
  cutting::BladeSweep sweep;
  const Eigen::Vector3d half = 0.5 * s.edge;
  sweep.a0 = previous_tip_ - half;
  sweep.b0 = previous_tip_ + half;
  sweep.a1 = s.position - half;
  sweep.b1 = s.position + half;
  if (!cutting::sweep_problem(sweep).empty()) return;  // at rest or along its edge: nothing swept
  const auto& o = scene_.options();
  scene_.cut(sweep, o.blade ? o.blade_mode : hybrid::CutMode::remove);
}

void ViewLoop::fill_topology(ViewTopology& t) {
  const mesh::TetMesh& mesh = scene_.model().mesh();
  const ContactSurface& surface = scene_.surface();
  t.version = topology_version_;
  t.nodes = mesh.num_nodes();
  t.reference.resize(3 * static_cast<std::size_t>(t.nodes));
  for (int i = 0; i < t.nodes; ++i)
    for (int d = 0; d < 3; ++d) t.reference[3 * i + d] = static_cast<float>(mesh.nodes[i][d]);
  t.triangles.clear();
  for (int tri = 0; tri < surface.num_triangles(); ++tri)
    if (surface.live(tri))
      for (int a : surface.triangle(tri)) t.triangles.push_back(a);
}

void ViewLoop::publish(long frames) {
  // The surface changed (a cut, or node copies of a separating cut): a new topology version.
  const int n = scene_.model().num_nodes();
  if (scene_.model().cut_events().size() != cuts_seen_ || n != nodes_seen_) {
    cuts_seen_ = scene_.model().cut_events().size();
    nodes_seen_ = n;
    ++topology_version_;
  }
  ViewState& s = states_.back();
  if (s.topology.version != topology_version_) fill_topology(s.topology);
  const double* u = scene_.displacement();
  const auto& X = scene_.model().mesh().nodes;
  s.positions.resize(3 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) s.positions[3 * i + d] = static_cast<float>(X[i][d] + u[3 * i + d]);
  s.region.clear();
  if (const regions::RegionTracker* r = scene_.regions(); r && r->active()) {
    const auto& region = r->active()->region();
    s.region.assign(n, 0);
    for (int i = 0; i < n && i < static_cast<int>(region.interior.size()); ++i)
      if (region.interior[i]) s.region[i] = 1;
    for (int i : region.interface)
      if (i < n) s.region[i] = 2;
  }
  const long last = record_.frames - 1;
  s.frame = frames;
  s.time = frames * scene_.options().frame_step;
  s.tip = record_.probe[last];
  s.force = record_.force[last];
  s.contact = record_.contact[last] != 0;
  s.blade = blade_;
  s.compute_mean = window_sum_ / std::max(1L, window_frames_);
  s.compute_max = window_max_;
  s.start_lag_max = lag_max_;
  s.window_frames = window_frames_;
  s.deadline_misses = deadline_misses_;
  s.events = static_cast<long>(scene_.events().size());
  s.cuts = static_cast<long>(scene_.model().cut_events().size());
  s.samples = samples_seen_;
  s.samples_dropped = dropped_.load(std::memory_order_relaxed);
  states_.publish();
  window_sum_ = window_max_ = lag_max_ = 0;
  window_frames_ = 0;
}

void ViewLoop::write_trajectory(const std::string& path) const {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw InputError(path + ": cannot be written (the pointer session's trajectory)");
  std::fprintf(f, "# haptic_sim view: the tool tip of every frame, t x y z (s, m); replay with input kind \"recorded\"\n");
  const double h = scene_.options().frame_step;
  for (long k = 0; k < record_.frames; ++k) {
    const Eigen::Vector3d& p = record_.probe[k];
    std::fprintf(f, "%.17g %.17g %.17g %.17g\n", k * h, p.x(), p.y(), p.z());
  }
  if (std::fclose(f) != 0) throw InputError(path + ": cannot be written (the pointer session's trajectory)");
}

}  // namespace softsim::haptic
