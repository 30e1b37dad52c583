#include "common/particles.hpp"

#include <algorithm>

namespace duet {

void Particles::start_from_rest() {
  std::fill(velocity.begin(), velocity.end(), Vec2::Zero());
  std::fill(displacement.begin(), displacement.end(), Vec2::Zero());
  std::fill(strain.begin(), strain.end(), Mat3::Zero());
}

void Particles::resize(std::size_t n) {
  position.resize(n, Vec2::Zero());
  velocity.resize(n, Vec2::Zero());
  displacement.resize(n, Vec2::Zero());
  mass.resize(n, 0.0);
  volume.resize(n, 0.0);
  density.resize(n, 0.0);
  stress.resize(n, Mat3::Zero());
  strain.resize(n, Mat3::Zero());
  body.resize(n, -1);
  material.resize(n, -1);
  internal.values.resize(n * internal.width, 0.0);
}

}  // namespace duet
