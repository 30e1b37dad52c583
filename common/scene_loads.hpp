#pragma once
// The scene's loads on particles, the same for every method: each load (a total force in N/m,
// piecewise linear in time) is shared equally by the particles of its body that lie initially in
// its box [min, max].

#include <cstddef>
#include <vector>

#include "common/particles.hpp"
#include "common/scene.hpp"

namespace duet {

/// For each scene load, the indices of the particles that carry it. Throws InputError naming the
/// load when its box holds no particle of its body.
using LoadedParticles = std::vector<std::vector<std::size_t>>;
LoadedParticles loaded_particles(const Scene& scene, const Particles& particles);

/// Zeroes `force` and adds every load's share at `time` to its particles.
void apply_loads(const Scene& scene, const LoadedParticles& loaded, double time,
                 std::vector<Vec2>& force);

}  // namespace duet
