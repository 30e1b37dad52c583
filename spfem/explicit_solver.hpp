#pragma once
// The explicit SPFEM step (Zhang 2018 slides, "Computational cycle of eSPFEM", Algorithm 1;
// Yuan et al. 2019): (re)mesh the nodes (Delaunay + alpha shape), build the node-based smoothing
// cells, critical time step (Gershgorin bound, step 3), smoothed velocity gradients (step 4),
// stress update through the shared constitutive library (step 5), internal forces (step 6), M a =
// F_ext - F_int and the central-difference update of velocities then positions (step 7). Nodes are
// the particles: stress and internal variables live on them. This class knows nothing of the scene
// file: spfem/method.cpp translates a Scene into an EspfemSetup.

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "common/json.hpp"
#include "common/particles.hpp"
#include "common/scene.hpp"
#include "common/tensor.hpp"
#include "common/timers.hpp"
#include "constitutive/model.hpp"
#include "spfem/nodal_discretisation.hpp"
#include "spfem/node_contact.hpp"
#include "spfem/stiffness_stabilisation.hpp"

namespace duet::spfem {

/// The step of each rule on an undistorted square lattice at safety 1, over dp / c (c the P-wave
/// speed): the cell-size rule's is 1 (the cell's side is dp); the Gershgorin bound's is 0.70,
/// 0.685 of the true limit 2 / omega_max (asserted by the test
/// TimeStep.GershgorinStepOnALatticeIsItsStatedFractionOfDpOverC). duet check estimates a run's
/// steps from it.
inline double lattice_step_over_dp_per_c(SpfemTimeStep rule) {
  return rule == SpfemTimeStep::gershgorin ? 0.70 : 1.0;
}

/// The factor on the undamped critical step that keeps central differences stable with a linear
/// bulk viscosity b1: omega dt <= 2 (sqrt(1 + xi^2) - xi) with xi = b1 (Abaqus Theory Manual,
/// "Explicit dynamic analysis": the stability limit with bulk viscosity); 1 without it.
inline double bulk_viscosity_step_factor(double b1) {
  return b1 > 0.0 ? std::sqrt(1.0 + b1 * b1) - b1 : 1.0;
}

/// The method options are the scene's [spfem] section (common/scene.hpp): alpha_factor,
/// time_step_safety, damping (viscous, 1/s), local_damping (Cundall, -), stabilisation (-),
/// stiffness_stabilisation (-), remesh every-step | angle, remesh_angle (deg),
/// remesh_angle_fraction (-).
struct EspfemSetup {
  duet::SpfemOptions options;
  double spacing = 0.0;                                      // dp, m
  Vec2 gravity = Vec2::Zero();                               // m/s^2
  std::vector<std::unique_ptr<constitutive::Model>> models;  // by material index
  std::vector<NodeBoundary> boundaries;                      // walls, then rigid bodies
  bool axisymmetric = false;  // x = r about the axis x = 0 (Scene::formulation)
};

/// The step's counters; the mesh's are in NodalDiscretisation::counters().
struct EspfemCounters {
  long steps = 0;
  double dt_min = 0.0;
  double dt_max = 0.0;
  long contacts_max = 0;
  double energy_reference = 0.0;  // kinetic + 0.5 sum A_k sigma:eps after the first step
  double energy_drift_max = 0.0;  // max |E - E_ref| / E_ref since then
  long stress_limited_steps = 0;  // steps whose dt the stress-increment limit set
  long inserted_nodes = 0;        // added along walls (spfem.wall_node_gap)
};

class ExplicitSolver {
 public:
  explicit ExplicitSolver(EspfemSetup setup);

  /// Orients the boundaries, sizes every buffer. Particles must have position, velocity, mass,
  /// volume, density, stress, material and internal variables set.
  void initialise(Particles& particles);

  /// Advances one step from `time`; returns dt. Throws NumericalFailure (common/solver.hpp).
  double step(Particles& particles, double time);

  /// Gravity loading: steps for `duration` seconds with an added viscous damping -damping m v
  /// (1/s) and walls held still, then zeroes velocities, displacements and strains.
  void settle(Particles& particles, double duration, double damping);

  /// Replaces the material models by models of the same kinds and internal variables (a
  /// strength reduced during the run: common/strength_reduction.hpp); the next step uses them.
  void use_models(std::vector<std::unique_ptr<constitutive::Model>> models);

  /// External force on each node (N/m), e.g. a scene load; zero unless set. Read every step.
  std::vector<Vec2>& external_force() { return external_force_; }

  /// Force of the soil on each boundary of the setup (N/m), in the order of setup.boundaries.
  const std::vector<Vec2>& boundary_forces() const { return boundary_force_; }
  const std::vector<NodeBoundary>& boundaries() const { return discretisation_.boundaries(); }
  const Timers& timers() const { return timers_; }
  const EspfemCounters& counters() const { return counters_; }
  const AlphaMesh& mesh() const { return discretisation_.mesh(); }
  const SmoothingCells& cells() const { return discretisation_.cells(); }
  const NodalDiscretisation& discretisation() const { return discretisation_; }
  /// Kinetic energy plus 0.5 sum_k A_k sigma_k : eps_k (the stored energy of a linear elastic
  /// body from a stress-free state), on the current mesh, plus the stiffness stabilisation's
  /// energy W at the positions of the last force evaluation.
  double energy(const Particles& particles) const;
  /// Counters and timings for metrics.json.
  Json diagnostics() const;

  /// `duet run --resume` (common/solver.hpp): the counters, the energy reference, the reactions
  /// and the walls' attachments (and a kept mesh), keys "solver.*"; a frame is a restart point
  /// (NodalDiscretisation::restart_point).
  void save_state(StateBag& state) const;
  void restore_state(const StateBag& state, std::size_t nodes);
  void restart_point() { discretisation_.restart_point(); }

 private:
  /// Node k's velocity gradient in 3-D: the smoothed in-plane L_k and, axisymmetric, the hoop
  /// rate of stretching v_r,k / r_k in the out-of-plane (theta theta) slot (its ring's
  /// circumference grows with its radius; the nodes stand off the axis,
  /// NodalDiscretisation::fill_ring).
  Mat3 full_velocity_gradient(const Particles& particles, std::size_t k) const {
    Mat3 l = Mat3::Zero();
    l.topLeftCorner<2, 2>() = velocity_gradient_[k];
    // Axisymmetric: the smoothed hoop rate sum_l v_r,l h_kl (spfem/smoothing.hpp)
    if (setup_.axisymmetric) l(2, 2) = smoothed_hoop_rate(cells(), particles.velocity, k);
    return l;
  }
  double time_step(const Particles& particles);
  double cell_size_time_step(const Particles& particles) const;
  double gershgorin_time_step(const Particles& particles);
  void update_stress(Particles& particles, double dt);
  void assemble_forces(const Particles& particles);
  void add_stabilisation(const Particles& particles);
  void integrate(Particles& particles, double time, double dt);
  /// spfem.wall_node_gap: adds nodes along the walls where their row has drawn apart, and
  /// extends the per-node arrays to them (the parents' means).
  void insert_nodes(Particles& particles);

  EspfemSetup setup_;
  NodalDiscretisation discretisation_;   // boundaries, mesh, wall strips, smoothing cells
  std::vector<std::size_t> n_internal_;  // per material

  std::vector<Mat2> velocity_gradient_;
  std::vector<double> wave_speed_;  // per node, m/s
  std::vector<double>
      block_modulus_;  // per node: M = |lambda| + 2 G or the model's tangent bound (Pa)
  std::vector<double> stiffening_;     // per node: M / |sigma| (0: stiffness not stress-bound)
  std::vector<double> cell_weight_;    // per cell: A_k M_k sum_m |b_km|, time-step scratch
  std::vector<double> gradient_norm_;  // per smoothing entry: |b_km|, time-step scratch
  std::vector<Vec2> internal_force_;
  std::vector<Vec2> stabilisation_force_;
  std::vector<Vec2> external_force_;
  std::vector<Mat3> scratch_stress_;
  std::vector<Mat3>
      viscous_stress_;  // sigma + the bulk viscosity's pressure (spfem.bulk_viscosity)
  std::vector<Vec2> scratch_force_;
  std::vector<double> triangle_area_;
  std::vector<Mat2> triangle_stress_;               // stabilising stress per triangle
  std::vector<std::array<Vec2, 3>> triangle_grad_;  // grad N_a per triangle
  // Stiffness stabilisation (spfem/stiffness_stabilisation.hpp)
  std::vector<Vec2> reference_position_;  // x - u: the nodes' initial positions
  std::vector<Vec2> stiffness_force_;     // -dW/dx
  StiffnessStabilisationScratch stiffness_scratch_;
  double stiffness_energy_ = 0.0;  // W at the last force evaluation (J/m)

  std::vector<Vec2> boundary_force_;

  double damping_ = 0.0;  // 1/s, only while settling
  bool settling_ = false;
  Timers timers_;
  EspfemCounters counters_;
  bool energy_reference_set_ = false;
};

}  // namespace duet::spfem
