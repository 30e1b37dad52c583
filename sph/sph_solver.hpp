#pragma once
// The SPH step for soils (Peng 2015; Bui 2008): momentum in the symmetric stress form with
// artificial viscosity and artificial stress, velocity gradient in the symmetric difference form
// handed to the shared constitutive library, dummy / ghost particles at walls, Verlet or leapfrog
// time integration with the variable time step of Peng 2015 eqs 36-37. This class knows nothing
// of the scene file: sph/method.cpp translates a Scene into an SphSetup.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/particles.hpp"
#include "common/state_bag.hpp"
#include "common/tensor.hpp"
#include "common/timers.hpp"
#include "constitutive/model.hpp"
#include "sph/dummy_velocity.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbours.hpp"
#include "sph/pair_terms.hpp"
#include "sph/rigid_contact.hpp"
#include "sph/walls.hpp"

namespace duet::sph {

/// The method options are the scene's [sph] section (common/scene.hpp): kernel, h/dp, alpha,
/// beta, artificial stress b, CFL number, sound speed, dummy layers, dummy-particle stress
/// (sigma-max: Peng 2015 eq 31; bui: the stress of the interacting soil particle), integrator
/// (verlet: Peng 2015 eqs 32-35 with the constitutive rate form; leapfrog: kick, drift and the
/// incremental objective update with return mapping), continuity (simhypo-sand eq 24), dummy
/// velocity (wall: Peng 2015 section 4.2; extrapolated: Morris 1997 / Bui 2008).
struct SphSetup {
  duet::SphOptions options;
  double spacing = 0.0;                                      // dp, m
  Vec2 gravity = Vec2::Zero();                               // m/s^2
  std::vector<std::unique_ptr<constitutive::Model>> models;  // by material index
  std::vector<WallSpec> walls;  // walls and rigid bodies with prescribed motion
  std::vector<FrictionalBodySpec> frictional_bodies;  // simhypo eqs 39-40 (sph/rigid_contact.hpp)
  // Axisymmetric (x = r about the axis x = 0, y = z; Particles::mass is the ring's): the r-z
  // plane's SPH over the ring masses with the hoop terms (Garcia-Senz et al. 2009; sph/README.md,
  // "Axisymmetric").
  bool axisymmetric = false;
};

struct SphCounters {
  long steps = 0;
  long penetrations_last_step = 0;
  long penetrations_max = 0;      // most particles behind a wall in any one step
  long penetrations_total = 0;    // particle-steps behind a wall
  long symmetry_reflections = 0;  // particles brought back across a symmetry plane (all steps)
  std::size_t dummy_particles = 0;
  std::size_t ghost_particles_max = 0;
  std::size_t neighbours_max = 0;  // longest neighbour row (within 2h + skin)
  long neighbour_builds = 0;       // Verlet-list rebuilds (every step would equal steps)
  double dt_min = 0.0;
  double dt_max = 0.0;
};

class SphSolver {
 public:
  explicit SphSolver(SphSetup setup);

  /// Places dummy particles, orients walls, sizes every buffer. Particles must have position,
  /// mass, density, volume, stress and material set.
  void initialise(Particles& particles);

  /// Advances one step from `time`; returns dt. Throws NumericalFailure (common/solver.hpp).
  double step(Particles& particles, double time);

  /// Gravity loading (Peng 2015 section 5.3): steps for `duration` seconds with a velocity
  /// damping force -damping m v (damping in 1/s), then zeroes velocities, displacements and
  /// strains and restarts the integrator, so the run starts from the equilibrium stress.
  void settle(Particles& particles, double duration, double damping);

  /// Replaces the material models by models of the same kinds and internal variables (a
  /// strength reduced during the run: common/strength_reduction.hpp); the next step uses them.
  void use_models(std::vector<std::unique_ptr<constitutive::Model>> models);

  /// External force on each soil particle (N/m), e.g. a scene load; zero unless set. Read at
  /// every step.
  std::vector<Vec2>& external_force() { return external_force_; }

  /// Force of the soil on each wall of the setup (N/m), in the order of setup.walls.
  const std::vector<Vec2>& wall_forces() const { return wall_force_; }
  const std::vector<WallSpec>& walls() const { return setup_.walls; }
  /// Frictional rigid bodies: their reactions (force of the soil on each body, N/m) and state.
  const RigidContact& rigid_contact() const { return contact_; }
  /// Wall time per phase: neighbours (walls, ghosts, the working-order copy, Verlet-list
  /// rebuilds), forces (pair loop), constitutive (stress update, time integration, checks).
  const Timers& timers() const { return timers_; }
  const SphCounters& counters() const { return counters_; }
  const Kernel& kernel() const { return kernel_; }
  const duet::SphOptions& options() const { return setup_.options; }
  /// Current boundary particle positions, for output and tests: the dummies, then the ghost
  /// candidates of the current neighbour list (a candidate acts only while its soil particle
  /// lies within 2h in front of the wall).
  const std::vector<Vec2>& boundary_positions() const { return boundary_position_; }
  /// Acceleration of each soil particle in the last step (m/s^2).
  const std::vector<Vec2>& accelerations() const { return acceleration_; }
  /// The velocity gradient of soil particle i that the last stress update used (or the next
  /// will use): eq 21's in-plane block and, axisymmetric, the hoop rate v_r / r in (2, 2).
  Mat3 full_velocity_gradient(std::size_t i) const;

  /// `duet run --resume` (common/solver.hpp): the walls and dummies where they are, the rigid
  /// bodies' contact state, the integrator's last step (Verlet's n - 1 state), the counters, keys
  /// "solver.*". A frame is a restart point: the next step builds its neighbour lists anew (in
  /// an order of the positions alone), as a resumed run must.
  void save_state(StateBag& state) const;
  void restore_state(const StateBag& state);
  void restart_point() { rebuild_ = true; }

 private:
  using PairData = detail::PairData;  // the pair loops' packed copy of a particle
  using SymR = detail::SymR;          // Peng 2015 eq 29 artificial stress R
  /// The force pass's constants for one step (sph_solver.cpp).
  struct ForcePass;

  void update_walls(double time, double dt);
  void select_ghosts(const Particles& particles);
  /// Copies the pair loop's inputs into work_ (working order); returns the largest squared
  /// displacement of a working entry or wall point since the last neighbour build.
  double gather(const Particles& particles);
  void rebuild_neighbours(const Particles& particles);
  /// The force pass (README, step 3): eq 30's acceleration of every soil particle, with Verlet
  /// eq 21's velocity gradient and eq 24's density rate, and the walls' forces.
  void pair_loop(const Particles& particles);
  /// Pass 1: each soil pair once, both ends' shares scattered into the thread's own buffer,
  /// ghosts on their row's particle; returns the number of threads that ran it.
  int soil_pair_pass(const ForcePass& pass);
  /// Pass 1's row k (working order) into the thread's buffers `sum` and `wall_force`.
  void soil_pair_row(std::size_t k, const ForcePass& pass, detail::PairSum* sum,
                     Vec2* wall_force) const;
  /// Pass 2: each soil particle's shares of the n_team threads summed, its dummies added, the
  /// results written to its driver index; returns the largest squared acceleration.
  double particle_pass(const ForcePass& pass, std::size_t n_team);
  /// The dummy particles of row k added to its sums `s`, their reactions to `wall_force`.
  void dummy_pairs(std::size_t k, const ForcePass& pass, detail::PairSum& s,
                   Vec2* wall_force) const;
  double time_step() const;
  /// sph.dummy_velocity = "extrapolated": replaces the velocity of dummy pj (of wall `wall`) seen
  /// from soil particle pi by Morris 1997 / Bui 2008's (sph/dummy_velocity.hpp); `line` caches
  /// pi's nearest segment of that wall between calls.
  void extrapolate_dummy_velocity(const PairData& pi, int wall, WallLine& line, PairData& pj) const;
  /// Leapfrog: v += dt a, x += dt v.
  void kick_drift(Particles& particles, double dt);
  /// Leapfrog: velocity gradient and density rate of the velocities after kick_drift
  /// (velocity_gradient_pass.cpp).
  void velocity_gradient_pass(const Particles& particles);
  /// Stress (and, with Verlet, the motion) update and the checks.
  void advance(Particles& particles, double dt);
  /// A particle that ended a step behind a symmetry plane becomes its mirror image (its ghost):
  /// position, velocity and stress reflected across the plane.
  void reflect_across_symmetry_planes(Particles& particles);
  /// Axisymmetric: NumericalFailure if a soil particle has reached the axis (r <= 0), where its
  /// ring has no radius.
  void check_off_axis(const Particles& particles) const;
  /// Eq 21's velocity gradient and eq 24's density rate of soil particle i (driver index) from
  /// its pair sums s and working copy p; axisymmetric, over its ring and with the hoop rate.
  void set_rates(std::size_t i, const PairData& p, const detail::PairSum& s);

  SphSetup setup_;
  Kernel kernel_;
  double h_ = 0.0;
  double skin_ = 0.0;                    // Verlet-list skin, m
  std::vector<std::size_t> n_internal_;  // per material
  std::vector<WallGeometry> geometry_;
  std::vector<std::vector<Vec2>> wall_reference_;  // wall points at the last neighbour build

  // Boundary particles: dummies (fixed count, moving with their wall), then the ghost
  // candidates chosen at the last neighbour build (every soil particle that could come within
  // 2h in front of a free-slip segment before the next build).
  std::size_t n_dummy_ = 0;
  std::vector<Vec2> dummy_position_;
  std::vector<Vec2> dummy_velocity_;
  std::vector<std::int32_t> dummy_wall_;
  std::vector<std::uint32_t> ghost_source_;  // per candidate: soil particle mirrored
  std::vector<std::uint32_t> ghost_wall_;    // per candidate: wall
  // per candidate: segment of that wall, or with kVertexGhost the vertex starting that segment
  std::vector<std::uint32_t> ghost_segment_;
  static constexpr std::uint32_t kVertexGhost = 0x80000000u;
  // per candidate: -1, or the symmetry plane (wall index) across which its ghost is mirrored
  // again: the corner's image, where a free-slip wall meets a symmetry plane
  std::vector<std::int32_t> ghost_plane_;
  std::vector<Vec2> boundary_position_;  // dummies, then ghost candidates (output only)
  std::size_t n_active_ghosts_ = 0;

  // Working order: order_[k] is the soil particle at working position k (sorted by cell at the
  // last neighbour build); ghosts follow at n + g, dummies at n + n_ghost + d.
  std::vector<std::uint32_t> order_;
  std::vector<PairData> work_;
  std::vector<SymR> work_r_;
  std::vector<std::int32_t> work_wall_;  // per working index: wall of a boundary particle, or -1
  std::vector<Vec2> work_reference_;     // working positions at the last neighbour build
  std::vector<Vec2> all_position_;
  CellList cells_;
  NeighbourLists neighbours_;
  bool rebuild_ = true;
  // The leapfrog's velocity pass runs at the positions the next step's pair loop sees: it keeps
  // each pair's kernel gradient factor (grad_i W_ij = f r_ij), aligned with the neighbour rows
  // (row k at k * stride, early part then late part; only pairs within 2h are written), for the
  // pair loop to reuse. Valid only while gradient_cached_: set by the velocity pass, cleared by a
  // neighbour rebuild, by a gather that finds any working position changed (drift, moving walls
  // and their dummies and ghosts, anything the driver did), by initialise and by settle.
  std::vector<double> gradient_factor_;
  bool gradient_cached_ = false;

  // Per soil particle (driver's index) results of the pair loop.
  std::vector<Vec2> acceleration_;
  std::vector<Vec2> external_force_;
  std::vector<Mat2> velocity_gradient_;
  std::vector<double> hoop_rate_;  // axisymmetric only: v_r / r (empty in plane strain)
  std::vector<double> density_rate_;
  double acceleration_max_ = 0.0;
  long penetrations_ = 0;  // soil particles behind a wall after the last update
  // Per thread, per soil particle (working order): the pair loop's sums of eqs 21, 30 and 24
  // and eq 31's smallest normal stresses among the soil neighbours.
  std::vector<detail::PairSum> pair_sum_;
  // Per thread, per wall: force of the soil on the wall.
  std::vector<Vec2> wall_force_scratch_;
  std::vector<Vec2> wall_force_;
  // Frictional rigid bodies; their outlines follow the walls in geometry_.
  RigidContact contact_;

  // Verlet history (n - 1).
  bool first_step_ = true;
  double previous_dt_ = 0.0;
  std::vector<Vec2> velocity_old_;
  std::vector<Mat3> stress_old_;
  std::vector<Mat3> strain_old_;
  std::vector<double> density_old_;
  std::vector<Vec2> scratch_velocity_;
  std::vector<Mat3> scratch_stress_;
  std::vector<Mat3> scratch_strain_;
  std::vector<double> scratch_density_;
  std::vector<double> void_ratio_old_;
  std::vector<int> void_ratio_slot_;  // per material: slot of "void_ratio" or -1

  double damping_ = 0.0;  // 1/s, only while settling
  bool settling_ = false;
  Timers timers_;
  SphCounters counters_;
  double w_dp_ = 1.0;        // W(dp) for the artificial stress (eq 28)
  double exponent_n_ = 1.0;  // n = W(0) / W(dp)
};

}  // namespace duet::sph
