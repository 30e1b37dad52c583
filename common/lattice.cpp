#include "common/lattice.hpp"

#include <cmath>

#include "common/geometry.hpp"

namespace duet {

namespace {

/// Calls visit(centre) for every lattice cell centre of the body that lies inside it.
template <class Visit>
void for_each_sample(const Body& body, double dp, Visit&& visit) {
  Vec2 lo, hi;
  bounding_box(body.outline, lo, hi);
  // Cells per side; the small allowance keeps a side of exactly k dp at k cells despite rounding.
  const auto n_x = static_cast<long>(std::ceil((hi.x() - lo.x()) / dp - 1e-9));
  const auto n_y = static_cast<long>(std::ceil((hi.y() - lo.y()) / dp - 1e-9));
  for (long j = 0; j < n_y; ++j) {
    for (long i = 0; i < n_x; ++i) {
      const Vec2 centre =
          lo + dp * Vec2(static_cast<double>(i) + 0.5, static_cast<double>(j) + 0.5);
      if (point_in_polygon(centre, body.outline)) visit(centre);
    }
  }
}

}  // namespace

std::size_t count_body_samples(const Scene& scene, std::size_t body_index) {
  std::size_t count = 0;
  for_each_sample(scene.bodies[body_index], scene.spacing, [&](const Vec2&) { ++count; });
  return count;
}

double estimated_particles(const Scene& scene) {
  double area = 0.0;
  for (const Body& body : scene.bodies) area += std::abs(signed_area(body.outline));
  return area / (scene.spacing * scene.spacing);
}

void sample_body(const Scene& scene, std::size_t body_index, Particles& particles) {
  const Body& body = scene.bodies[body_index];
  const Material& material = scene.materials[static_cast<std::size_t>(body.material_index)];
  const double dp = scene.spacing;
  std::vector<Vec2> centres;
  for_each_sample(body, dp, [&](const Vec2& centre) { centres.push_back(centre); });
  const std::size_t first = particles.size();
  particles.resize(first + centres.size());
  for (std::size_t k = 0; k < centres.size(); ++k) {
    const std::size_t p = first + k;
    particles.position[p] = centres[k];
    particles.velocity[p] = body.initial_velocity;
    particles.displacement[p] = Vec2::Zero();
    particles.volume[p] = dp * dp;
    particles.mass[p] = material.density * dp * dp;
    particles.density[p] = material.density;
    particles.stress[p] = Mat3::Zero();
    particles.strain[p] = Mat3::Zero();
    particles.body[p] = static_cast<std::int32_t>(body_index);
    particles.material[p] = static_cast<std::int32_t>(body.material_index);
  }
}

Particles sample_bodies(const Scene& scene) {
  Particles particles;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) sample_body(scene, b, particles);
  return particles;
}

}  // namespace duet
