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
// Failure detection: an inverted TLED or corotational element (J ≤ 0) is caught in the step it
// happens; a non-finite displacement in the step it appears; an inverted linear element and
// energy growth (kinetic + strain energy above `energy_growth_limit` × (initial energy +
// external work)) at every energy sample. Each throws NumericalError naming the step, the
// quantity and the limit.
#include <array>
#include <functional>
#include <vector>

#include <Eigen/Core>

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
};

struct EnergySample {
  double time = 0;
  // ½ v⁻·M v⁺ with the half-step velocities v∓ around `time`: the kinetic energy that central
  // differences conserve exactly for a linear undamped system (½ v·M v up to O(Δt²)).
  double kinetic = 0;
  double strain = 0;
  double external_work = 0;  // by loads, gravity, the probe and moving constraints since t = 0 (trapezoidal)
  double dissipated = 0;     // initial energy + work − kinetic − strain (damping, and O(Δt²) error)
};

struct ExplicitTiming {
  int threads = 1;
  double wall_seconds = 0;      // the whole stepping loop, energy samples and snapshots included
  double steps_per_second = 0;  // steps / (wall_seconds − sample_seconds): the stepping alone
  std::array<double, fem::kNumElementKinds> kernel_seconds{};  // summed over threads
  std::array<int, fem::kNumElementKinds> element_counts{};
  double node_seconds = 0;  // nodal gather and update, summed over threads
  double sample_seconds = 0;  // energy samples, checks and snapshot callbacks

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
  double dt = 0;
  double time = 0;                   // steps × dt
  std::vector<double> displacement;  // u(time), 3 per node
  std::vector<double> velocity;      // (u(time) − u(time − dt)) / dt
  std::vector<EnergySample> energies;
  std::vector<double> trajectory_time;
  std::vector<std::vector<Eigen::Vector3d>> trajectories;  // [trajectory node][sample]
  std::vector<double> probe_time;
  std::vector<Eigen::Vector3d> probe_force;  // spring force on the node
  std::vector<Eigen::Vector3d> reactions;    // per constraint: F_int − R at `time` (quasi-static)
  ExplicitTiming timing;
};

using SnapshotFn = std::function<void(int step, double time, const std::vector<double>& u,
                                      const std::vector<double>& v)>;

class ExplicitSolver {
 public:
  // `masses`: lumped nodal masses (see lumped_mass.hpp). Throws InputError for bad options.
  ExplicitSolver(fem::ElementSet& elements, std::vector<double> masses, const Scene& scene,
                 const ExplicitOptions& options);

  // Initial displacement and velocity (3 per node); default zero. Constrained components take
  // their prescribed values regardless.
  void set_initial_state(std::vector<double> u0, std::vector<double> v0);

  ExplicitResult run(const SnapshotFn& snapshot = {});

 private:
  struct LoadEntry {
    int node;
    int load;
    std::array<bool, 3> free;
  };

  void build_schedule();
  template <bool kGravity>
  void update_node(int i, const double* up, const double* uc, double* un, double& check, double f[3]) const;
  template <bool kGravity>
  void update_nodes(const int* list, int begin, int split, int end, int step, const double* up, const double* uc,
                    double* un, double& check);
  void update_nodes(const int* list, int begin, int split, int end, int step, const double* up, const double* uc,
                    double* un, double& check);
  void update_special(int i, int step, const double f[3], const double* up, const double* uc, double* un);
  EnergySample sample_energy(int n_done, const double* u_before, const double* u_mid, const double* u_after,
                             double& bound_kinetic, double& min_j, int& min_j_element);
  double external_work() const;

  fem::ElementSet& elements_;
  std::vector<double> mass_;
  Scene scene_;
  ExplicitOptions opt_;
  int n_ = 0;
  std::vector<double> A_, B_, C_, Am_;
  bool gravity_ = false;
  std::vector<ConstrainedDof> dofs_;
  std::vector<char> moving_;  // per constraint: prescribed value non-zero and ramped
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
  std::array<bool, 3> probe_free_ = {true, true, true};
  Eigen::Vector3d probe_previous_ = Eigen::Vector3d::Zero();
  std::vector<double> u0_, v0_;
  // Per-run recording targets.
  std::vector<std::vector<Eigen::Vector3d>>* trajectories_ = nullptr;
  std::vector<Eigen::Vector3d>* probe_force_ = nullptr;
};

}  // namespace softsim::dynamics
