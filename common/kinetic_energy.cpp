#include "common/kinetic_energy.hpp"

#include <algorithm>
#include <functional>
#include <vector>

namespace duet {

KineticEnergyCarriers kinetic_energy_carriers(const Particles& particles) {
  KineticEnergyCarriers c;
  const std::size_t n = particles.size();
  std::vector<double> e(n);
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    e[i] = 0.5 * particles.mass[i] * particles.velocity[i].squaredNorm();
    total += e[i];
    c.mass += particles.mass[i];
    if (e[i] > e[c.largest]) c.largest = i;
  }
  if (!(total > 0.0)) {  // nothing moves: only the mass is known
    KineticEnergyCarriers still;
    still.mass = c.mass;
    return still;
  }
  c.speed = particles.velocity[c.largest].norm();
  c.position = particles.position[c.largest];
  std::sort(e.begin(), e.end(), std::greater<>());
  double carried = 0.0;
  while (c.half < n && carried < 0.5 * total) carried += e[c.half++];
  return c;
}

Json KineticEnergyCarriers::to_json() const {
  Json j = Json::object();
  j["half"] = static_cast<long>(half);
  j["largest_particle"] = static_cast<long>(largest);
  j["largest_speed"] = speed;
  j["largest_position"] = Json::array({position.x(), position.y()});
  j["mass"] = mass;
  return j;
}

}  // namespace duet
