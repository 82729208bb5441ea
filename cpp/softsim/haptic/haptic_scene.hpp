#pragma once
// The haptic scene (001 §3 in 3-D): a tool tip moved by the user pulls a point of the organ's
// surface through a spring, and the spring's force is both the model's input and the force
// sent back to the device, once per haptic frame (1 kHz):
//   1. the tip position p arrives; the contact point x_c follows the closest point of the
//      deformed surface (contact_surface.hpp),
//   2. f = k (p − x_c) acts on the contact triangle's nodes (w_a f), held over the frame,
//   3. the model advances one frame: as many explicit substeps as the critical step requires
//      (000 eqs. 34–35), all nodes every substep (the whole model), or the linked asynchronous
//      regions of 001 §5 (the primary region around the contact every substep, the secondary
//      region linear and coupled: regions/region_solver.hpp),
//   4. the device receives the force on the tool, −k (p − x_c⁺), at the updated state.
// The model is a dhd_sim scene (hybrid::DhdScene, the same engine and config). A live scene never
// stops: a numerical failure is reported as an event, the model goes back to rest, and the
// frames go on.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/haptic/contact_surface.hpp"
#include "softsim/hybrid/dhd_scene.hpp"
#include "softsim/regions/region_tracker.hpp"

namespace softsim::haptic {

enum class ContactMode {
  grasp,  // the tip holds the surface point it first touches (forceps): pulls as well as pushes
  attach, // as grasp, but glued: the spring pulls the same material point (triangle and
          // barycentric weights of the first touch) for the whole contact, it never slides
  push,   // unilateral: contact starts when the tip is below the surface, ends when it would pull
  tool,   // the model's first rigid tool (boundary.tools) sits at the tip; the force the tissue
          // exerts on it (frictionless contact with its surface nodes) goes to the device
};

// How the probe's spring is coupled to the model within a frame.
enum class SpringCoupling {
  frame,    // f = k (p − x_c) from the frame's start, held over its substeps: an explicit coupling
            // at the frame step, stable only for a spring soft against the tissue's response
            // within a frame (it chatters or blows up when stiff)
  substep,  // the spring is part of the model's explicit step: f = k (p − x_c(u_n)) at every
            // substep n with the tip p held over the frame (a virtual coupling at the substep
            // rate), stable for any k up to the explicit step's own limit
};

struct HapticOptions {
  double frame_step = 1e-3;       // s (1 kHz)
  double probe_stiffness = 100;   // k (N/m); not used by ContactMode::tool
  SpringCoupling spring_coupling = SpringCoupling::frame;
  // ContactMode::tool: the tool's centre is at tip + tool_offset (e.g. [0, 0, R] puts a sphere's
  // lowest point at a tip pressing down).
  Eigen::Vector3d tool_offset = Eigen::Vector3d::Zero();
  ContactMode contact = ContactMode::grasp;
  // A blade on the tool: an edge from tip − blade_edge/2 to tip + blade_edge/2 that cuts,
  // each frame, the elements its sweep from the previous tip to the current one crosses.
  bool blade = false;
  Eigen::Vector3d blade_edge = Eigen::Vector3d::Zero();  // m
  // Remove the elements it crosses, or separate the mesh along the faces nearest its sweep
  // (the model's config must then allow separation: DhdConfig::separates).
  hybrid::CutMode blade_mode = hybrid::CutMode::remove;
  // Linked asynchronous regions (001 §5) instead of the whole model: the primary region around
  // the contact every frame, the secondary region linear and coupled (regions/region_solver.hpp).
  bool use_regions = false;
  regions::RegionOptions regions;
  // Regions with contact "tool": the primary interior holds every node within this distance of
  // the tool's surface (m), the nodes it may touch before the next frame's check; < 0: a quarter
  // of regions.radius.
  double tool_margin = -1;
};

struct FrameEvent {
  long frame = 0;
  std::string message;  // the numerical failure the model recovered from
};

class HapticScene {
 public:
  // The model's explicit step is the configured one (or safety × Δt_cr) shortened so that a whole
  // number of substeps fills a frame. InputError for a static model config or bad options.
  HapticScene(std::shared_ptr<const mesh::TetMesh> mesh, hybrid::DhdConfig model, const HapticOptions& options);

  // Regions: builds the primary region around the surface point nearest to `probe` before the
  // frames begin (an input whose start is known), so that its set-up is not part of a frame.
  // Otherwise the first contact builds it. Nothing for the whole model.
  void prepare(const Eigen::Vector3d& probe);
  // One haptic frame with the tip at `probe` (m, world): returns the force on the tool (N).
  Eigen::Vector3d frame(const Eigen::Vector3d& probe);
  // Back to rest, no contact, frame 0.
  void reset();
  // Between frames: a cut by element removal along `sweep` in the current geometry (the whole
  // model's, or the regions' published one); the surface and the regions follow it.
  hybrid::DhdScene::CutEvent cut(const cutting::BladeSweep& sweep, hybrid::CutMode mode = hybrid::CutMode::remove);

  const HapticOptions& options() const { return options_; }
  int substeps() const { return substeps_; }
  double dt() const { return model_->dt(); }
  long frames_done() const { return frames_; }
  // Contact "tool": whether the rigid tool touched a node at the end of the last frame; else
  // whether the spring holds a surface point.
  bool in_contact() const { return options_.contact == ContactMode::tool ? tool_touching_ : in_contact_; }
  const SurfacePoint& contact() const { return contact_; }
  const std::vector<FrameEvent>& events() const { return events_; }
  hybrid::DhdScene& model() { return *model_; }
  const hybrid::DhdScene& model() const { return *model_; }
  const ContactSurface& surface() const { return *surface_; }
  // The linked regions (null: the whole model): the active region, how often regions were
  // built and handed over, and their statistics.
  const regions::RegionTracker* regions() const { return regions_.get(); }
  // The model's displacement now (3 per node): the whole model's, or the regions' published one
  // (its far field as of the last due recovery, solved on this call if it was deferred: a scene
  // whose far field nobody reads never solves it; the forces are the same either way).
  const double* displacement() const;
  // The time at which the model made its i-th cut event (model().cut_events()[i]), s: the
  // whole model's explicit time, or with regions the frame's start (the regions step, not the
  // model).
  double cut_time(std::size_t i) const { return cut_times_.at(i); }
  // The blade's sweeps so far (one per frame the tool moved) and their wall time (s).
  struct BladeStats {
    long sweeps = 0;
    double seconds = 0, max_seconds = 0;
  };
  const BladeStats& blade_stats() const { return blade_stats_; }
  // Regions built beside the frames (RegionOptions::build_in_background): the frames whose
  // contact lay outside the current region's interior while its region was being built, the
  // spring's force then acting at the last contact point inside it, or (a new contact there)
  // on no tissue.
  struct LiveStats {
    long frames_held = 0;
    long frames_unapplied = 0;
  };
  const LiveStats& live_stats() const { return live_stats_; }

 private:
  void update_contact(const Eigen::Vector3d& probe);
  // The whole model's frame with the spring at every substep (SpringCoupling::substep).
  void whole_model_spring_frame(const Eigen::Vector3d& probe);
  // The displacement to read the contact triangle `nodes` in: the regions' published one when
  // it is current there (primary nodes), else displacement().
  const double* contact_reading(const std::array<int, 3>& nodes) const;
  // The blade's cut of this frame, then the surface brought up to the model's cuts (the blade's
  // and the config's scheduled ones); a contact on a triangle that left the surface ends.
  void cut_with_blade(const Eigen::Vector3d& probe);
  void follow_cuts();
  // Regions: the config's scheduled cuts whose time falls in this frame, at its start (the whole
  // model makes them at the first explicit step that reaches their time).
  void scheduled_cuts();
  // Contact "tool" with the regions: the region covers what the tool may touch, one frame.
  Eigen::Vector3d tool_frame_with_regions(const Eigen::Vector3d& centre);
  double tool_margin() const;
  // The model at rest and no contact; frames and events kept (recovery from a failure).
  void back_to_rest();

  std::shared_ptr<const mesh::TetMesh> mesh_;
  HapticOptions options_;
  int substeps_ = 1;
  std::unique_ptr<hybrid::DhdScene> model_;
  std::optional<ContactSurface> surface_;  // on the model's mesh (a separating model's own copy)
  bool in_contact_ = false;     // the spring's contact (contact_ is valid while it holds)
  bool tool_touching_ = false;  // contact "tool"
  SurfacePoint contact_;
  long frames_ = 0;
  std::vector<FrameEvent> events_;
  Eigen::Vector3d previous_tip_ = Eigen::Vector3d::Zero();
  bool has_previous_tip_ = false;
  std::size_t cuts_seen_ = 0;
  std::vector<double> cut_times_;  // per cut event the surface followed
  double model_time_ = 0;          // the regions' state time: a frame's start during it
  BladeStats blade_stats_;  // the model's cut events the surface has followed
  LiveStats live_stats_;
  // Background builds: the last contact point inside the current region, where the spring acts
  // while the contact is outside it (contact_held_).
  SurfacePoint held_point_;
  bool contact_held_ = false;
  double runaway_distance_ = 0;  // m: the mesh's bounding-box diagonal (divergence beyond it)
  std::vector<dynamics::AppliedForce> applied_;  // sized once: the contact triangle's nodes
  std::unique_ptr<regions::RegionTracker> regions_;  // the linked regions, or null
  std::size_t next_scheduled_cut_ = 0;  // regions: the config's cuts made so far
  std::vector<int> tool_nodes_;          // regions: scratch for the tool's node sets
};

// The explicit step and substep count of a frame: the largest step ≤ `dt_limit` that divides
// `frame_step` into whole substeps.
struct FrameSubsteps {
  int substeps = 1;
  double dt = 0;
};
FrameSubsteps frame_substeps(double frame_step, double dt_limit);

}  // namespace softsim::haptic
