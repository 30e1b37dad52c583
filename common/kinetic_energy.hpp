#pragma once
// Kinetic energy of the particles and its history over a run: the "at rest" criterion of the
// collapse benchmarks (kinetic energy at the end below a fraction of its peak) read from every
// step rather than from the output frames.

#include <cstddef>

#include "common/json.hpp"
#include "common/particles.hpp"

namespace duet {

/// 0.5 sum_i m_i |v_i|^2 (J per metre of thickness).
inline double kinetic_energy(const Particles& particles) {
  double e = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    e += particles.mass[i] * particles.velocity[i].squaredNorm();
  }
  return 0.5 * e;
}

/// Who carries the kinetic energy at one instant. A deposit still settling spreads it over many
/// particles; a few particles thrown off the body hold most of it (an espfem node thrown up from
/// the front of collapse-bui, still in flight at the end: benchmarks/RESULTS.md).
struct KineticEnergyCarriers {
  std::size_t half = 0;     // the fewest particles that carry at least half of it; 0: none moves
  std::size_t largest = 0;  // the particle with the most kinetic energy (row)
  double speed = 0.0;       // its speed (m/s)
  Vec2 position = Vec2::Zero();
  double mass = 0.0;  // kg/m: every particle's mass together

  Json to_json() const;
};

KineticEnergyCarriers kinetic_energy_carriers(const Particles& particles);

/// Peak, time of the peak and latest value of the kinetic energy, one record per step; who
/// carries it at the end (set once the run ends).
struct KineticEnergyRecord {
  double peak = 0.0;
  double peak_time = 0.0;
  double end = 0.0;
  KineticEnergyCarriers end_carriers;

  void record(double time, double energy) {
    end = energy;
    if (energy > peak) {
      peak = energy;
      peak_time = time;
    }
  }
  /// end / peak; 0 when the particles never moved.
  double end_over_peak() const { return peak > 0.0 ? end / peak : 0.0; }

  Json to_json() const {
    Json j = Json::object();
    j["peak"] = peak;
    j["peak_time"] = peak_time;
    j["end"] = end;
    j["end_over_peak"] = end_over_peak();
    j["end_carriers"] = end_carriers.to_json();
    return j;
  }
};

}  // namespace duet
