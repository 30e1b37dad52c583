#pragma once
// The energy put into the particles since the start, for the driver's blow-up check: the kinetic
// and elastic energy they started with (the elastic part computed by the caller from the models:
// common/ knows none), plus the work of gravity (sum_i m_i g . (x_i - x_i0)), of the scene's
// loads and of moving walls and rigid bodies (the power -R . v, R the soil's force on the
// boundary, integrated over each step by the trapezoidal rule). Dissipation and the strain energy
// stored on the way only keep the kinetic energy below it; the factor of the check leaves room for
// the estimate of the initial elastic energy (a tangent modulus for a nonlinear model) and the
// time integration of the work. A method that makes energy (a tensile instability, a contact
// that pumps particles) shows as kinetic energy well above it.

#include <optional>
#include <string>
#include <vector>

#include "common/json.hpp"
#include "common/particles.hpp"
#include "common/scene.hpp"
#include "common/scene_loads.hpp"
#include "common/solver.hpp"
#include "common/state_bag.hpp"

namespace duet {

class EnergyBudget {
 public:
  EnergyBudget(const Scene& scene, const Particles& particles, double initial_elastic);

  /// Empty when every input is computed; otherwise why the budget is incomplete (a radial wall,
  /// whose work would need its traction, not its net force).
  const std::optional<std::string>& incomplete() const { return incomplete_; }

  /// Advances the work integrals to `time` with the state and reactions at that time.
  void record(double time, const Particles& particles, const std::vector<Reaction>& reactions);

  /// Energy put in so far (J per metre of thickness).
  double input() const {
    return initial_kinetic_ + initial_elastic_ + gravity_work_ + boundary_work_ + load_work_;
  }
  double initial_elastic() const { return initial_elastic_; }
  double initial_kinetic() const { return initial_kinetic_; }
  double gravity_work() const { return gravity_work_; }
  double boundary_work() const { return boundary_work_; }
  double load_work() const { return load_work_; }
  /// An energy below which no check fires, so that a run that barely moves never trips on
  /// round-off: 1e-6 M (L / T)^2, M the particles' mass, L the domain's diagonal, T the end time
  /// (a millionth of the energy of the whole mass crossing the domain once in the run).
  double floor() const { return floor_; }

  /// Keeps the largest kinetic / max(input, floor) seen: how close a run came to the check.
  void observe(double kinetic);
  double peak_ratio() const { return peak_ratio_; }
  double peak_ratio_time() const { return peak_ratio_time_; }

  Json to_json() const;

  /// The integrals so far into / from a frame's state (`duet run --resume`), key "energy_budget".
  void save_state(StateBag& state) const;
  void restore_state(const StateBag& state);

 private:
  double boundary_power(double time, const std::vector<Reaction>& reactions) const;
  double load_power(double time, const Particles& particles) const;

  const Scene& scene_;
  std::vector<Vec2> initial_position_;
  LoadedParticles loaded_;
  std::optional<std::string> incomplete_;
  double initial_kinetic_ = 0.0;
  double initial_elastic_ = 0.0;
  double gravity_work_ = 0.0;
  double boundary_work_ = 0.0;
  double load_work_ = 0.0;
  double floor_ = 0.0;
  double time_ = 0.0;
  double boundary_power_ = 0.0;  // at time_
  double load_power_ = 0.0;
  double peak_ratio_ = 0.0;
  double peak_ratio_time_ = 0.0;
};

}  // namespace duet
