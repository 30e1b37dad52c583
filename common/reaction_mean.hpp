#pragma once
// The reactions a measure samples from an inertial run: their mean over the interval since the
// last sample (the impulse over its duration), not the last step's. An explicit step's contact
// forces swing from step to step (the cavity's wall stress at dp 0.25 m through espfem ranged
// 1.9-5.7 c_u within a quarter of a second), so one step's value is noise; a load cell reads
// the low-passed force. A quasi-static run's reactions are equilibrium forces at that instant and
// are sampled as they are.

#include <vector>

#include "common/solver.hpp"
#include "common/state_bag.hpp"

namespace duet {

struct ReactionMean {
  std::vector<Reaction> impulse;  // sum of F dt since the last sample, per named reaction
  double span = 0.0;              // s
  std::vector<Reaction> last;     // the mean the last sample took

  /// One step of length dt with the reactions at its end.
  void add(const std::vector<Reaction>& reactions, double dt);
  /// The mean since the last sample, and a fresh start. When no time has passed since (the run's
  /// last sample at the time of the loop's), the mean that sample took; before any step,
  /// `reactions` as they are.
  std::vector<Reaction> take(const std::vector<Reaction>& reactions);

  void save_state(StateBag& state) const;
  void restore_state(const StateBag& state);
};

}  // namespace duet
