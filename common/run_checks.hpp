#pragma once
// Failure detection owned by the driver, the same for every method: non-finite state, a particle
// leaving the domain, a particle crossing a wall, a body lifting off a fixed no-slip wall, kinetic
// energy beyond the energy put in. A failed check is a result (status "failed", exit 3), not a
// crash. The last two take their thresholds from the scene's [checks].

#include <optional>
#include <string>
#include <vector>

#include "common/energy_budget.hpp"
#include "common/particles.hpp"
#include "common/scene.hpp"

namespace duet {

struct StateProblem {
  std::string reason;
  long particle = -1;
  Vec2 position = Vec2::Zero();
};

class StateChecks {
 public:
  /// `initial`: the particles at t = 0 (which of them touch a fixed no-slip wall).
  StateChecks(const Scene& scene, const Particles& initial);

  /// Checks the state after a step from `previous_time` to `time`; `previous_position` are the
  /// positions before the step. Returns the first problem found, or nothing.
  std::optional<StateProblem> check(const Particles& particles,
                                    const std::vector<Vec2>& previous_position,
                                    double previous_time, double time) const;

  /// The body lifting off a fixed no-slip wall: more than lift_off_fraction of the particles
  /// within one spacing of the wall at t = 0 are now further than lift_off_distance spacings
  /// from it. A no-slip wall holds what touches it; soil leaving it as a whole is a blow-up (the
  /// weightless footing that rose off its base).
  std::optional<StateProblem> check_lift_off(const Particles& particles) const;

 private:
  struct Contact {
    std::size_t wall;
    std::vector<std::size_t> particles;  // within one spacing of the wall at t = 0
  };
  const Scene& scene_;
  std::vector<Contact> contacts_;
};

/// Kinetic energy above kinetic_energy_factor x the energy put in, and above the budget's floor:
/// the reason, or nothing (also nothing when the check is off or the budget incomplete). `unit`:
/// the energies' unit in the message (energy_unit of the scene's formulation).
std::optional<std::string> energy_runaway(const RunCheckOptions& options, double kinetic,
                                          const EnergyBudget& budget, const char* unit = "J/m");

}  // namespace duet
