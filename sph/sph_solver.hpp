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
#include "common/tensor.hpp"
#include "common/timers.hpp"
#include "constitutive/model.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbours.hpp"
#include "sph/walls.hpp"

namespace duet::sph {

/// The method options are the scene's [sph] section (common/scene.hpp): kernel, h/dp, alpha,
/// beta, artificial stress b, CFL number, sound speed, dummy layers, dummy-particle stress
/// (sigma-max: Peng 2015 eq 31; bui: the stress of the interacting soil particle), integrator
/// (verlet: Peng 2015 eqs 32-35 with the constitutive rate form; leapfrog: kick, drift and the
/// incremental objective update with return mapping), continuity (simhypo-sand eq 24).
struct SphSetup {
  duet::SphOptions options;
  double spacing = 0.0;                                      // dp, m
  Vec2 gravity = Vec2::Zero();                               // m/s^2
  std::vector<std::unique_ptr<constitutive::Model>> models;  // by material index
  std::vector<WallSpec> walls;  // walls and rigid bodies with prescribed motion
};

struct SphCounters {
  long steps = 0;
  long penetrations_last_step = 0;
  long penetrations_max = 0;    // most particles behind a wall in any one step
  long penetrations_total = 0;  // particle-steps behind a wall
  std::size_t dummy_particles = 0;
  std::size_t ghost_particles_max = 0;
  std::size_t neighbours_max = 0;
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

  /// External force on each soil particle (N/m), e.g. a scene load; zero unless set. Read at
  /// every step.
  std::vector<Vec2>& external_force() { return external_force_; }

  /// Force of the soil on each wall of the setup (N/m), in the order of setup.walls.
  const std::vector<Vec2>& wall_forces() const { return wall_force_; }
  const std::vector<WallSpec>& walls() const { return setup_.walls; }
  /// Wall time per phase: neighbours, forces (pair loop), constitutive (stress update and
  /// time integration), other (walls, ghosts, checks).
  const Timers& timers() const { return timers_; }
  const SphCounters& counters() const { return counters_; }
  const Kernel& kernel() const { return kernel_; }
  const duet::SphOptions& options() const { return setup_.options; }
  /// Current boundary (dummy, then ghost) particle positions, for output and tests.
  const std::vector<Vec2>& boundary_positions() const { return boundary_position_; }
  /// Acceleration of each soil particle in the last step (m/s^2).
  const std::vector<Vec2>& accelerations() const { return acceleration_; }

 private:
  void update_boundary(const Particles& particles, double time, double dt);
  void find_neighbours(const Particles& particles);
  void pair_loop(const Particles& particles);
  double time_step() const;
  void advance(Particles& particles, double dt);
  long count_penetrations(const Particles& particles) const;

  SphSetup setup_;
  Kernel kernel_;
  double h_ = 0.0;
  std::vector<std::size_t> n_internal_;  // per material
  std::vector<WallGeometry> geometry_;

  // Boundary particles: dummies first (fixed count), then ghosts (rebuilt each step).
  std::size_t n_dummy_ = 0;
  std::vector<Vec2> boundary_position_;
  std::vector<Vec2> boundary_velocity_;
  std::vector<std::int32_t> boundary_wall_;
  std::vector<std::int32_t> ghost_source_;  // per ghost: soil particle mirrored
  std::vector<Vec2> ghost_normal_;          // per ghost: wall normal
  std::vector<Vec2> dummy_reference_;       // dummy positions at t = 0 (walls translate)

  // All positions (soil, then boundary) for the neighbour search.
  std::vector<Vec2> all_position_;
  CellList cells_;
  NeighbourLists neighbours_;

  // Per soil particle results of the pair loop.
  std::vector<Vec2> acceleration_;
  std::vector<Vec2> external_force_;
  std::vector<Mat2> velocity_gradient_;
  std::vector<double> density_rate_;
  // Per thread, per wall: force of the soil on the wall.
  std::vector<Vec2> wall_force_scratch_;
  std::vector<Vec2> wall_force_;

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

  // Per soil particle, refreshed before the pair loop: in-plane stress / rho^2 and the
  // artificial stress R of Peng 2015 eq 29.
  std::vector<Mat2> stress_over_rho2_;
  std::vector<Mat2> artificial_r_;

  double damping_ = 0.0;  // 1/s, only while settling
  bool settling_ = false;
  Timers timers_;
  SphCounters counters_;
  double w_dp_ = 1.0;        // W(dp) for the artificial stress (eq 28)
  double exponent_n_ = 1.0;  // n = W(0) / W(dp)
};

}  // namespace duet::sph
