#pragma once
// Failure detection owned by the driver, the same for every method: non-finite state, a particle
// leaving the domain, a particle crossing a wall. A failed check is a result (status "failed",
// exit 3), not a crash.

#include <optional>
#include <string>
#include <vector>

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
  explicit StateChecks(const Scene& scene);

  /// Checks the state after a step from `previous_time` to `time`; `previous_position` are the
  /// positions before the step. Returns the first problem found, or nothing.
  std::optional<StateProblem> check(const Particles& particles,
                                    const std::vector<Vec2>& previous_position,
                                    double previous_time, double time) const;

 private:
  const Scene& scene_;
};

}  // namespace duet
