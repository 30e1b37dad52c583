#include "common/reaction_mean.hpp"

namespace duet {

void ReactionMean::add(const std::vector<Reaction>& reactions, double dt) {
  if (impulse.size() != reactions.size()) {
    impulse = reactions;
    for (Reaction& r : impulse) r.force.setZero();
    span = 0.0;
  }
  for (std::size_t k = 0; k < reactions.size(); ++k) impulse[k].force += dt * reactions[k].force;
  span += dt;
}

std::vector<Reaction> ReactionMean::take(const std::vector<Reaction>& reactions) {
  if (span > 0.0 && impulse.size() == reactions.size()) {
    last = reactions;
    for (std::size_t k = 0; k < last.size(); ++k) last[k].force = impulse[k].force / span;
  } else if (last.size() != reactions.size()) {
    last = reactions;  // nothing yet: the reactions as they are
  }
  for (std::size_t k = 0; k < last.size(); ++k) last[k].name = reactions[k].name;  // resumed
  for (Reaction& r : impulse) r.force.setZero();
  span = 0.0;
  return last;
}

void ReactionMean::save_state(StateBag& state) const {
  std::vector<Vec2> forces;
  for (const Reaction& r : impulse) forces.push_back(r.force);
  put(state, "driver.reaction_impulse", forces);
  put(state, "driver.reaction_span", span);
  std::vector<Vec2> last_forces;
  for (const Reaction& r : last) last_forces.push_back(r.force);
  put(state, "driver.reaction_last_mean", last_forces);
}

void ReactionMean::restore_state(const StateBag& state) {
  std::vector<Vec2> forces;
  get(state, "driver.reaction_impulse", forces);
  impulse.assign(forces.size(), Reaction{});
  for (std::size_t k = 0; k < forces.size(); ++k) impulse[k].force = forces[k];
  span = scalar(state, "driver.reaction_span");
  get(state, "driver.reaction_last_mean", forces);
  last.assign(forces.size(), Reaction{});
  for (std::size_t k = 0; k < forces.size(); ++k) last[k].force = forces[k];
}

}  // namespace duet
