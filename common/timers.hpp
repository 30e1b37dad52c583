#pragma once
// Named per-phase wall-clock timers for a solver step, and a scoped guard that charges one phase.
// Cheap (one clock read at each end of a scope, steady_clock by default) and meant to be called
// from the single thread that drives the step, around its parallel regions, never inside them.

#include <array>
#include <cstddef>
#include <functional>
#include <string_view>
#include <utility>

#include "common/json.hpp"

namespace duet {

/// The phases a run reports in metrics.json "timing" (DESIGN.md). A method times the ones it has.
enum class Phase {
  neighbours,    // neighbour search (cell lists)
  constitutive,  // stress update of every particle through the soil model
  forces,        // momentum and continuity right-hand sides, boundary forces
  integration,   // time integration of positions, velocities, densities
  mesh,          // SPFEM triangulation / alpha shape / smoothing cells
  assembly,      // SPFEM internal force vector and tangent stiffness
  solve,         // linear (and Newton) solves
  output,        // HDF5 frames, series, metrics
  other,         // anything else worth separating (set-up, checks)
};
inline constexpr std::size_t n_phases = 9;

/// Lower-case name of a phase as it appears in metrics.json.
std::string_view phase_name(Phase phase);

/// Seconds from a monotonic clock with an arbitrary origin (std::chrono::steady_clock).
double steady_seconds();

class Timers {
 public:
  /// Returns seconds from any fixed origin; tests inject a fake one.
  using Clock = std::function<double()>;

  explicit Timers(Clock clock = steady_seconds) : clock_(std::move(clock)) {}

  double now() const { return clock_(); }
  /// Charge `seconds` of wall time to `phase` (one more timed interval).
  void add(Phase phase, double seconds);
  /// Add every phase of `other` to this one (e.g. a driver's output timers to a solver's).
  void add(const Timers& other);

  double seconds(Phase phase) const { return seconds_[index(phase)]; }
  long count(Phase phase) const { return count_[index(phase)]; }
  /// Sum over all phases.
  double total_seconds() const;
  void reset();

  /// {"neighbours": s, "constitutive": s, ...} with every phase, in the order of Phase (a phase a
  /// method does not have reads 0, so compare.csv gets the same columns for every method).
  Json to_json() const;

 private:
  static std::size_t index(Phase phase) { return static_cast<std::size_t>(phase); }
  Clock clock_;
  std::array<double, n_phases> seconds_{};
  std::array<long, n_phases> count_{};
};

/// Charges the wall time between its construction and its destruction (or stop()) to one phase:
/// `ScopedTimer t(timers, Phase::forces);`
class ScopedTimer {
 public:
  ScopedTimer(Timers& timers, Phase phase) : timers_(timers), phase_(phase), start_(timers.now()) {}
  ~ScopedTimer() { stop(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

  /// Charge now instead of at the end of the scope (later calls do nothing).
  void stop() {
    if (stopped_) return;
    stopped_ = true;
    timers_.add(phase_, timers_.now() - start_);
  }

 private:
  Timers& timers_;
  Phase phase_;
  double start_;
  bool stopped_ = false;
};

}  // namespace duet
