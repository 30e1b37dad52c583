#include "common/scene_loads.hpp"

#include <algorithm>

#include "common/geometry.hpp"
#include "common/input_error.hpp"

namespace duet {

LoadedParticles loaded_particles(const Scene& scene, const Particles& particles) {
  LoadedParticles loaded(scene.loads.size());
  for (std::size_t l = 0; l < scene.loads.size(); ++l) {
    const Load& load = scene.loads[l];
    for (std::size_t i = 0; i < particles.size(); ++i) {
      const Vec2& x = particles.position[i];
      if (particles.body[i] == load.body_index && (x.array() >= load.min.array()).all() &&
          (x.array() <= load.max.array()).all()) {
        loaded[l].push_back(i);
      }
    }
    if (loaded[l].empty()) {
      throw InputError("load." + load.name + ": no particle of body " + load.body +
                       " lies in its box");
    }
  }
  return loaded;
}

void apply_loads(const Scene& scene, const LoadedParticles& loaded, double time,
                 std::vector<Vec2>& force) {
  std::fill(force.begin(), force.end(), Vec2::Zero());
  for (std::size_t l = 0; l < scene.loads.size(); ++l) {
    const Vec2 share =
        schedule_value(scene.loads[l].force, time) / static_cast<double>(loaded[l].size());
    for (const std::size_t i : loaded[l]) force[i] += share;
  }
}

}  // namespace duet
