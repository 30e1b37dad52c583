#include "common/timers.hpp"

#include <chrono>
#include <numeric>

namespace duet {

std::string_view phase_name(Phase phase) {
  switch (phase) {
    case Phase::neighbours:
      return "neighbours";
    case Phase::constitutive:
      return "constitutive";
    case Phase::forces:
      return "forces";
    case Phase::integration:
      return "integration";
    case Phase::mesh:
      return "mesh";
    case Phase::assembly:
      return "assembly";
    case Phase::solve:
      return "solve";
    case Phase::output:
      return "output";
    case Phase::other:
      return "other";
  }
  return "unknown";
}

double steady_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

void Timers::add(Phase phase, double seconds) {
  seconds_[index(phase)] += seconds;
  ++count_[index(phase)];
}

void Timers::add(const Timers& other) {
  for (std::size_t k = 0; k < n_phases; ++k) {
    seconds_[k] += other.seconds_[k];
    count_[k] += other.count_[k];
  }
}

double Timers::total_seconds() const {
  return std::accumulate(seconds_.begin(), seconds_.end(), 0.0);
}

void Timers::reset() {
  seconds_.fill(0.0);
  count_.fill(0);
}

Json Timers::to_json() const {
  Json j = Json::object();
  for (std::size_t k = 0; k < n_phases; ++k) {
    j[phase_name(static_cast<Phase>(k))] = seconds_[k];
  }
  return j;
}

}  // namespace duet
