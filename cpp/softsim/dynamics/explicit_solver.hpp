#pragma once
// The explicit dynamic engine of DHD-FEA (000 §2.2.3–2.2.4): per step, element forces (any mix
// of kinds), nodal resultants (eq. 23) and the central-difference update (eq. 33) with lumped
// mass and mass-proportional damping. One step is a sweep over the element set's tiles: compute
// a tile's elements, then update the nodes that became ready, so the force buffer is read back
// while still in cache. Multithreaded with OpenMP: each thread sweeps a run of tiles, the nodes
// on the boundaries between runs wait for one barrier; two barriers per step, no atomics, and
// results bit-identical for any thread count. With ANP elements, a pre-pass (two more barriers)
// computes their nodal pressures first.
//
// Failure detection: an inverted TLED, ANP or corotational element (J ≤ 0) is caught in the step
// it happens, except the TLED and ANP elements of an inversion-robust law (stable neo-Hookean:
// ElementSet::inversion_allowed), for which inversion is a state like any other; a non-finite
// displacement in the step it appears; an inverted linear element and energy growth (kinetic +
// strain energy above `energy_growth_limit` × (initial energy + external work)) at every energy
// sample. Each throws NumericalError naming the step, the quantity and the limit; with a known
// critical step (ExplicitOptions::critical_step) one whose step exceeds the critical step of the
// last sound state says it is a step-size failure.
//
// Variable step: with `adapt_step` the step is re-estimated on the deformed mesh and shrinks
// when needed (see ExplicitOptions); the step change is the variable-step central difference
// (central_difference.hpp), and time() is then the sum of the steps taken.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "softsim/dynamics/contact_search.hpp"
#include "softsim/dynamics/scene.hpp"
#include "softsim/fem/element_set.hpp"

namespace softsim::dynamics {

struct ExplicitOptions {
  double dt = 0;
  int steps = 0;
  double damping_alpha = 0;  // D = α M (1/s)
  int threads = 1;
  int energy_interval = 100;  // steps between energy samples (and energy / linear-inversion checks)
  double energy_growth_limit = 2.0;
  std::vector<int> trajectory_nodes;
  int trajectory_interval = 1;
  int snapshot_interval = 0;  // 0: no snapshots
  // The critical step of the current state (000 eq. 34 on the deformed mesh, see
  // DeformedCriticalStep); empty: none known. With it, a failure whose step exceeds the critical
  // step of the last sound state is reported as a step-size failure, and with `adapt_step` the
  // step is re-estimated every `step_check_interval` steps: once the step in use exceeds the
  // current critical step, it becomes `step_safety` × that step (it only ever shrinks).
  std::function<double(const double* u)> critical_step;
  bool adapt_step = false;
  double step_safety = 0.9;
  int step_check_interval = 10;
  // Told which elements a cut removed (remove_elements), e.g. to drop them from the deformed
  // critical-step estimate above.
  std::function<void(const std::vector<int>& elements)> elements_removed;
  // Scheduled events (ascending times, s): advance() stops at the first step whose time reaches
  // event_times[k] and calls on_event(k) there, between steps (a cut scheduled by a config).
  std::vector<double> event_times;
  std::function<void(int event)> on_event;
  // Nodes whose three components are held by fixed constraints are neither gathered nor
  // integrated (their value is the constraint's); false updates them like the others, the
  // reference the skipping is tested and measured against (results equal bit for bit).
  bool skip_held_nodes = true;
  // Rigid tools: the broad phase finds the nodes near each tool (dynamics/contact_search.hpp);
  // false tests every node of every tool each step, the reference the search is tested and
  // measured against (results equal bit for bit).
  bool contact_search = true;
};

// What one cut event removed (ExplicitSolver::remove_elements).
struct CutReport {
  std::vector<int> elements;  // removed now (original indices)
  double mass = 0;            // kg that left with them
  double strain_energy = 0;   // stored in them at the cut (their element part; J)
  double kinetic_energy = 0;  // of the mass that left, at the half-step velocity before the cut (J)
  int detached_nodes = 0;     // nodes left without any element: they hold their place
  double seconds = 0;         // wall time of the local update
};

// One run of equal steps: from step `first_step` (at `time`) on, each step lasts `dt`.
struct StepSegment {
  int first_step = 0;
  double time = 0;
  double dt = 0;
};

struct EnergySample {
  double time = 0;
  // ½ v⁻·M v⁺ with the half-step velocities v∓ around `time`: the kinetic energy that central
  // differences conserve exactly for a linear undamped system (½ v·M v up to O(Δt²)).
  double kinetic = 0;
  double strain = 0;
  double external_work = 0;  // by loads, gravity, the probe and moving constraints since t = 0 (trapezoidal)
  double removed = 0;        // carried away by elements removed by cuts since t = 0 (CutReport)
  double dissipated = 0;     // initial energy + work − kinetic − strain − removed (damping, and O(Δt²) error)
};

struct ExplicitTiming {
  int threads = 1;
  double wall_seconds = 0;      // the whole stepping loop, energy samples and snapshots included
  double steps_per_second = 0;  // steps / (wall_seconds − sample_seconds): the stepping alone
  std::array<double, fem::kNumElementKinds> kernel_seconds{};  // summed over threads
  std::array<int, fem::kNumElementKinds> element_counts{};
  double node_seconds = 0;  // nodal gather and update, summed over threads
  double sample_seconds = 0;  // energy samples, checks and snapshot callbacks
  double contact_seconds = 0;  // rigid tools: broad and narrow phase (dynamics/explicit_contact.cpp)

  // Kernel time of one element of `kind` per step, and node-phase time of one node per step
  // (ns), over a run of `steps` steps; 0 without elements of that kind or without steps.
  double ns_per_element(int kind, int steps) const {
    const int n = element_counts[kind];
    return n > 0 && steps > 0 ? 1e9 * kernel_seconds[kind] / (double(n) * steps) : 0.0;
  }
  double ns_per_node(int num_nodes, int steps) const {
    return steps > 0 ? 1e9 * node_seconds / (double(num_nodes) * steps) : 0.0;
  }
};

struct ExplicitResult {
  int steps = 0;
  double dt = 0;                     // the first step
  double time = 0;                   // simulated time after `steps` steps (steps × dt at a constant step)
  std::vector<StepSegment> step_history;  // one entry per step size used, the first at step 0
  std::vector<double> displacement;  // u(time), 3 per node
  std::vector<double> velocity;      // (u(time) − u(time − dt)) / dt
  std::vector<EnergySample> energies;
  std::vector<double> trajectory_time;
  std::vector<std::vector<Eigen::Vector3d>> trajectories;  // [trajectory node][sample]
  std::vector<double> probe_time;
  std::vector<Eigen::Vector3d> probe_force;  // spring force on the node
  std::vector<Eigen::Vector3d> reactions;    // per constraint: F_int − R at `time` (quasi-static)
  // Per rigid tool (Scene::tools): the force the body exerts on it at each energy sample's time
  // (energies[k].time), and how many of its nodes it touched then.
  std::vector<std::vector<Eigen::Vector3d>> tool_force;
  std::vector<std::vector<int>> tool_contacts;
  ExplicitTiming timing;
};

// A force on one node, held from one advance() to the next (a tool's contact force spread over
// the nodes it touches, 001 §3's haptic input).
struct AppliedForce {
  int node = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N
};

using SnapshotFn = std::function<void(int step, double time, const std::vector<double>& u,
                                      const std::vector<double>& v)>;
// Called between chunks of steps (at most `energy_interval` steps apart) with the steps done so
// far and the simulated time; a caller prints progress from it. It must not touch the solver.
using ProgressFn = std::function<void(int steps_done, double time)>;

// Set-up once (constructor), then either run() — the whole configured run with its recordings,
// as dhd_sim does — or the stepping interface: advance(n) from the current state, with the
// prescribed displacements and the probe moved between calls and the state read in place.
// Both share one stepping loop (advance), so a run() equals the same number of steps advanced
// in any number of calls, bit for bit.
class ExplicitSolver {
 public:
  // `masses`: lumped nodal masses (see lumped_mass.hpp). Throws InputError for bad options.
  ExplicitSolver(fem::ElementSet& elements, std::vector<double> masses, const Scene& scene,
                 const ExplicitOptions& options);

  // Initial displacement and velocity (3 per node); default zero. Constrained components take
  // their prescribed values regardless. Takes effect at the next reset() (run() resets).
  void set_initial_state(std::vector<double> u0, std::vector<double> v0);
  // Instead: a central-difference state handed over from another solver (a moved region), u(0) =
  // `u_now` and u(−Δt) = `u_before` as given, with no start-up step, so the central difference
  // continues as if uninterrupted. Takes effect at the next reset(); set_initial_state clears it.
  void set_resumed_state(std::vector<double> u_now, std::vector<double> u_before);

  // The whole run of `options.steps` steps from the initial state, with trajectories, probe
  // force history, energy samples, snapshots and the final reactions.
  ExplicitResult run(const SnapshotFn& snapshot = {}, const ProgressFn& progress = {});

  // ---- stepping interface ----
  // Back to t = 0: the scene as constructed, the initial state and the start-up step of
  // 000 eq. 33 (u(−Δt)); energy samples, work and timing cleared. The constructor does not
  // step: the first advance() resets if nothing has yet.
  void reset();
  // `steps` more central-difference steps (000 eq. 33) from the current state. Energy samples
  // and the energy/inversion checks happen after steps 1, 1 + energy_interval, ... and after
  // step `options.steps`, as in run(). Throws NumericalError on a failure, after which the
  // state is undefined: reset() before stepping again.
  void advance(int steps, const SnapshotFn& snapshot = {}, const ProgressFn& progress = {});
  int steps_done() const { return n_done_; }
  double time() const { return time_at(n_done_); }
  // The step in use from now on (options().dt unless the step was re-estimated).
  double dt() const { return segments_.empty() ? opt_.dt : segments_.back().dt; }
  // Time after `step` steps, and the length of step `step` (from t_step to t_{step+1}), for the
  // steps since the last reset (the current step size beyond them).
  double time_at(int step) const;
  double step_size(int step) const;
  // The step sizes used since the last reset.
  const std::vector<StepSegment>& step_history() const { return segments_; }
  // Between steps: the step re-estimate now (ExplicitOptions::critical_step), as every
  // step_check_interval steps would do; nothing without adapt_step. After a change of the
  // critical step's function (a cut measured again).
  void recheck_step() {
    if (opt_.adapt_step && started_) check_step();
  }
  int num_nodes() const { return n_; }
  // The lumped nodal masses in use (after cuts: what they left).
  const std::vector<double>& masses() const { return mass_; }
  const ExplicitOptions& options() const { return opt_; }
  const Scene& scene() const { return scene_; }
  // u(time), 3 per node, in place: valid until the next advance() or reset().
  const double* displacement() const { return buf_[(n_done_ + 1) % 3].data(); }
  // (u(time) − u(time − Δt)) / Δt into `out` (3 per node); the initial velocity at step 0.
  void velocity(double* out) const;
  // Per constraint: F_int(u) − R at the current time (quasi-static: inertia left out). One
  // element pass over the whole set.
  std::vector<Eigen::Vector3d> reactions();
  // The probe spring's force on its node at the current state, k (tip(t) − u_node); zero
  // without a probe.
  Eigen::Vector3d probe_force() const;
  // Energy samples taken since the last reset.
  const std::vector<EnergySample>& energies() const { return energies_; }
  // Timing of the steps since the last reset.
  ExplicitTiming timing() const;

  // Between steps: constraint `c` holds `value` (m, the components it constrains) from the next
  // step on, its ramp dropped; its work is booked as for a moving constraint from then on.
  void set_prescribed_displacement(int c, const Eigen::Vector3d& value);
  // Between steps: the probe's tip sits at X_node + `tip_displacement` from the next step on.
  void set_probe_tip(const Eigen::Vector3d& tip_displacement);
  // Between steps: these forces act (on the components no constraint holds) from the next step
  // until the next call, replacing the previous set; any node, no set-up per node. Their work
  // F · Δu is booked exactly (the force is constant between calls). An empty set removes them.
  void set_applied_forces(const std::vector<AppliedForce>& forces);

  // Between steps: a cut by element removal. The element set drops the elements by a local
  // update (fem::ElementSet::remove_elements), their lumped mass ρ⁰V/4 leaves their corners and
  // only those nodes' central-difference coefficients are recomputed; a node left without any
  // element holds its place. Nothing global is rebuilt. The element eigenvalue bound behind
  // 000 eq. 34 cannot shrink (each remaining element keeps its own mass share and stiffness), so
  // the altitude estimate stays valid; the lumped system's own 2/ω_max may move toward that
  // bound (DhdScene measures it again when the step came from power iteration).
  // Permanent: reset() returns to t = 0 with the cut mesh. `mesh`: the element set's mesh.
  CutReport remove_elements(const mesh::TetMesh& mesh, const std::vector<int>& elements);
  double removed_energy() const { return removed_energy_; }

  // Between steps: a cut by separation along faces (cutting/separation.hpp). Each copy joins
  // the state as a new node (numbered after all others, in order) with its node's displacement
  // history u_{n−1}, u_n (so it moves on with the node's velocity), and the lumped masses
  // ρ⁰V/4 of the moved elements leave the node for the copy: mass, momentum and kinetic energy
  // are unchanged and nothing is removed. Only the two nodes' coefficients are recomputed; the
  // copy is updated after the mid-step barrier, and joins every rigid tool its node is listed
  // for. A node a constraint acts on cannot split (InputError). The element bound on the stable
  // step does not change: each element keeps its own mass share at every corner (as for
  // remove_elements).
  // `mesh`: the element set's mesh after the split.
  double split_nodes(const mesh::TetMesh& mesh, const std::vector<fem::ElementSet::NodeCopy>& copies);

  // ---- rigid tools (Scene::tools): frictionless kinematic contact (explicit_contact.cpp) ----
  // Between steps: tool k's centre sits at `centre` from the next step on, its travel dropped
  // (the haptic loop moves the tool this way).
  void set_tool_position(int k, const Eigen::Vector3d& centre);
  // The force the body exerts on tool k at the last step (minus the sum of the contact forces on
  // its nodes), and how many of its nodes were in contact then.
  Eigen::Vector3d tool_force(int k) const;
  int tool_contacts(int k) const;
  // The broad phase's state (how often it searched, how many nodes it lists).
  const ContactSearch& contact_search() const { return search_; }

 private:
  struct LoadEntry {
    int node;
    int load;
    std::array<bool, 3> free;
  };
  // Per-thread slots on separate cache lines.
  struct alignas(64) ThreadSlot {
    double min_j = 1e300;
    bool bad = false;
    std::array<double, fem::kNumElementKinds> kernel_seconds{};
    double node_seconds = 0;
    int timed_steps = 0;
  };

  void build_schedule();
  void start();
  void sample(const SnapshotFn& snapshot);
  template <bool kGravity, bool kApplied>
  void update_node(int i, const double* up, const double* uc, double* un, double& check, double f[3],
                   const Eigen::Vector3d& g) const;
  template <bool kGravity, bool kApplied>
  void update_nodes(const int* list, int begin, int split, int end, int step, const double* up, const double* uc,
                    double* un, double& check, const Eigen::Vector3d& g);
  void update_nodes(const int* list, int begin, int split, int end, int step, const double* up, const double* uc,
                    double* un, double& check, const Eigen::Vector3d& g);
  // Gravity acting at step `step` (scene gravity × its ramp; the scene's vector itself when
  // constant, so a constant gravity takes the same values bit for bit).
  Eigen::Vector3d gravity_at(int step) const;
  double gravity_potential(const double* u) const;  // G·u with G = M g (the full gravity)
  void book_gravity_work(int step, const double* uc);
  void update_special(int i, int step, const double f[3], const double* up, const double* uc, double* un);
  void mark_held_nodes();  // held_ from dofs_ and moving_
  void set_coefficients(double dt_before, double dt_after);
  void set_node_coefficients(int i);
  StepSegment segment_at(int step) const;
  void fire_due_events();
  void build_contacts(const std::vector<char>& constrained);
  void setup_contact_search();  // the broad phase over the contact entries
  // After every node's update of step `step`: moves the nodes that entered a tool out of it (see
  // RigidTool) and books the contact work, for the candidates the broad phase lists.
  void contact_pass(int step, const double* up, const double* uc, double* un);
  // Contact entry e of tool `tool` at `centre` (t_next, the time of un); `t`: the time of uc.
  void project_entry(int e, const RigidTool& tool, const Eigen::Vector3d& centre, int step, double t,
                     const double* up, const double* uc, double* un);
  void sample_trajectories(int i, int step, const double* un);
  void record_tool_forces();
  void check_step();
  std::string where(int step) const;
  [[noreturn]] void fail_step_size(int step, const double* u, const std::string& what) const;
  EnergySample sample_energy(int n_done, const double* u_before, const double* u_mid, const double* u_after,
                             double& bound_kinetic, double& min_j, int& min_j_element);
  double external_work(const double* u_mid) const;
  [[noreturn]] void fail_inversion(int step, double J, int element) const;

  fem::ElementSet& elements_;
  std::vector<double> mass_;
  Scene initial_scene_;  // as constructed: reset() returns to it
  Scene scene_;          // as driven between steps
  ExplicitOptions opt_;
  int n_ = 0;
  std::vector<double> A_, B_, C_, Am_;
  double coefficient_dt_before_ = 0, coefficient_dt_after_ = 0;  // the step pair A, B, C are for
  bool gravity_ = false;
  // Cuts: elements left per node (built at the first cut), the energy removed, the next event.
  std::vector<int> elements_left_;
  double removed_energy_ = 0;
  std::size_t next_event_ = 0;
  // Ramped gravity: its work is booked step by step while the ramp runs (trapezoidal, as for
  // loads), ½ (r(t_{s−1}) + r(t_s)) G·(u_s − u_{s−1}); after the ramp it is G·(u − u_b) on top,
  // u_b the last booked state. Both stay 0 for a constant gravity (work G·u, exact).
  bool gravity_ramped_ = false;
  double gravity_ramp_work_ = 0;
  double gravity_booked_potential_ = 0;  // G·u_b
  std::vector<ConstrainedDof> dofs_;
  std::vector<char> moving_;  // per constraint: prescribed value non-zero and ramped, or driven
  std::vector<char> held_;    // per node: all three components held by constraints none of which moves
  std::vector<LoadEntry> loads_;
  std::vector<int> element_ranges_;                    // per part, for the energy samples
  // Scratch of the energy samples, sized once: strain energy and J per element slot, and per part
  // the smallest J and its element.
  std::vector<double> slot_energy_, slot_volume_ratio_, part_min_j_;
  std::vector<int> part_min_j_element_;
  std::vector<int> tile_begin_;                        // per part: first tile
  std::vector<int> local_begin_, local_split_, local_nodes_;        // per tile: nodes updated right after it
  std::vector<int> deferred_begin_, deferred_split_, deferred_nodes_;  // per part: nodes updated after the barrier
  std::vector<int> pressure_nodes_;                    // per part: node range of the ANP pressure pass
  std::vector<int> dof_begin_, load_begin_, trajectory_begin_;  // per node: its special entries
  std::vector<int> trajectory_order_;  // trajectory entries sorted by node
  std::vector<double> dof_work_, load_work_;
  std::vector<double> dof_force_;  // force of each moving constrained dof at the previous step
  double probe_work_ = 0;
  // Rigid tools: per node, its contact entries (CSR over contacts_); per entry, the contact
  // force on the node at the last step (3 values) and its work, booked trapezoidally like a load's.
  struct ContactEntry {
    int tool;
    int node;
    Eigen::Vector3d position;  // the node's reference position X
  };
  ContactSearch search_;
  double contact_seconds_ = 0;
  std::vector<int> contact_begin_;
  std::vector<ContactEntry> contacts_;
  std::vector<double> contact_force_, contact_work_;
  std::vector<std::vector<Eigen::Vector3d>> tool_force_samples_;
  // Per tool: where set_tool_position moved it from, and the step that moves it (−1: none): the
  // tool's displacement over that step, which friction needs.
  std::vector<Eigen::Vector3d> tool_moved_from_;
  std::vector<int> tool_moved_at_;
  std::vector<std::vector<int>> tool_contact_samples_;
  std::array<bool, 3> probe_free_ = {true, true, true};
  Eigen::Vector3d probe_previous_ = Eigen::Vector3d::Zero();
  // Applied forces (set_applied_forces): F per dof, dense so the node update reads it
  // without a search; the nodes in use; the state their work is booked from.
  std::vector<double> applied_force_;
  std::vector<AppliedForce> applied_;
  std::vector<double> applied_from_;  // u (3 per applied node) when the set began to act
  double applied_work_ = 0;           // booked by the sets before the current one
  std::vector<char> constrained_;     // per dof
  std::vector<double> u0_, v0_;
  std::vector<double> u_before_;  // u(−Δt) of a resumed state (empty: the start-up step)
  double energy_floor_ = 0;  // energies below it are round-off (growth check)

  // The state: u_{n−1}, u_n, u_{n+1} rotate through buf_ (u_n = buf_[(n + 1) % 3]).
  std::array<std::vector<double>, 3> buf_;
  std::vector<double> v_start_;  // the initial velocity as imposed (constrained components zero)
  bool started_ = false;
  int n_done_ = 0;
  // Step sizes since the reset; the last segment is the current one. While `transition_`, the
  // coefficients are those of the step from the previous size to the current one (step
  // segments_.back().first_step).
  std::vector<StepSegment> segments_;
  bool transition_ = false;
  std::vector<EnergySample> energies_;
  double initial_energy_ = 0, initial_bound_ = 0;
  std::vector<ThreadSlot> slots_;
  double loop_seconds_ = 0, sample_seconds_ = 0;
  std::vector<double> snapshot_velocity_;
  // Per-run recording targets (run() only).
  std::vector<std::vector<Eigen::Vector3d>>* trajectories_ = nullptr;
  std::vector<Eigen::Vector3d>* probe_force_ = nullptr;
};

}  // namespace softsim::dynamics
