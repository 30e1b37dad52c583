#include "common/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "common/geometry.hpp"

namespace duet {

namespace {

/// Rings of the polar lattice (see lattice.hpp): calls visit(centre, volume) for each point
/// inside the outline.
template <class Visit>
void for_each_polar_sample(const Body& body, double dp, Visit&& visit) {
  const Vec2 o = body.lattice_centre;
  double first = 0.0;  // inner radius: the nearest vertex, or 0 with the centre inside
  double last = 0.0;
  if (!point_in_polygon(o, body.outline)) first = std::numeric_limits<double>::infinity();
  for (const Vec2& v : body.outline) {
    first = std::min(first, (v - o).norm());
    last = std::max(last, (v - o).norm());
  }
  const auto rings = static_cast<long>(std::ceil((last - first) / dp - 1e-9));
  for (long k = 0; k < rings; ++k) {
    const double r = first + (static_cast<double>(k) + 0.5) * dp;
    // Points per ring a multiple of 4, so that the axes through the centre (a quarter model's
    // planes of symmetry) fall midway between two points, half an arc spacing from each.
    const long n = 4 * std::max(1L, std::lround(0.5 * std::numbers::pi * r / dp));
    const double step = 2.0 * std::numbers::pi / static_cast<double>(n);
    const double volume = r * step * dp;  // the ring's annulus shared equally
    for (long j = 0; j < n; ++j) {
      const double angle = (static_cast<double>(j) + 0.5) * step;
      const Vec2 x = o + r * Vec2(std::cos(angle), std::sin(angle));
      if (point_in_polygon(x, body.outline)) visit(x, volume);
    }
  }
}

/// Calls visit(centre, volume) for every sample of the body that lies inside it.
template <class Visit>
void for_each_sample(const Body& body, double dp, Visit&& visit) {
  if (body.lattice == LatticeKind::polar) {
    for_each_polar_sample(body, dp, visit);
    return;
  }
  Vec2 lo, hi;
  bounding_box(body.outline, lo, hi);
  // Cells per side; the small allowance keeps a side of exactly k dp at k cells despite rounding.
  const auto n_x = static_cast<long>(std::ceil((hi.x() - lo.x()) / dp - 1e-9));
  const auto n_y = static_cast<long>(std::ceil((hi.y() - lo.y()) / dp - 1e-9));
  for (long j = 0; j < n_y; ++j) {
    for (long i = 0; i < n_x; ++i) {
      const Vec2 centre =
          lo + dp * Vec2(static_cast<double>(i) + 0.5, static_cast<double>(j) + 0.5);
      if (point_in_polygon(centre, body.outline)) visit(centre, dp * dp);
    }
  }
}

}  // namespace

std::size_t count_body_samples(const Scene& scene, std::size_t body_index) {
  std::size_t count = 0;
  for_each_sample(scene.bodies[body_index], scene.spacing, [&](const Vec2&, double) { ++count; });
  return count;
}

double estimated_particles(const Scene& scene) {
  double area = 0.0;
  for (const Body& body : scene.bodies) area += std::abs(signed_area(body.outline));
  return area / (scene.spacing * scene.spacing);
}

std::vector<std::string> lattice_misfits(const Scene& scene) {
  std::vector<std::string> lines;
  const double dp = scene.spacing;
  for (const Body& body : scene.bodies) {
    if (body.shape != ShapeKind::rectangle || body.lattice != LatticeKind::square) continue;
    const Vec2 drawn = body.max - body.min;
    // Rows kept per axis: cell centres (i + 1/2) dp strictly inside the side (for_each_sample's
    // rule), so the sampled side is that many spacings.
    const Vec2 sampled(std::ceil(drawn.x() / dp - 0.5 - 1e-9) * dp,
                       std::ceil(drawn.y() / dp - 0.5 - 1e-9) * dp);
    std::string text;
    for (int axis = 0; axis < 2; ++axis) {
      const double misfit = drawn[axis] - sampled[axis];  // > 0: the lattice ends short of max
      if (std::abs(misfit) <= 1e-6 * drawn[axis]) continue;
      char part[300];
      std::snprintf(part, sizeof part,
                    "%s%s %.6g m is %.4g spacings: the lattice's last %s ends %.3g m %s %s = %.6g",
                    text.empty() ? "" : "; ", axis == 0 ? "width" : "height", drawn[axis],
                    drawn[axis] / dp, axis == 0 ? "column" : "row", std::abs(misfit),
                    misfit > 0.0 ? "short of" : "beyond", axis == 0 ? "max x" : "max y",
                    body.max[axis]);
      text += part;
    }
    if (text.empty()) continue;
    char tail[300];
    std::snprintf(
        tail, sizeof tail,
        " (spacing %.6g m). The sampled body is %.6g x %.6g m, area %+.2g %% against the "
        "drawn one; whatever rests on that side starts off it, and measures against "
        "the drawn size carry the difference; a spacing that divides both sides fits exactly",
        dp, sampled.x(), sampled.y(),
        100.0 * (sampled.x() * sampled.y() / (drawn.x() * drawn.y()) - 1.0));
    lines.push_back("body." + body.name + ": " + text + tail);
  }
  return lines;
}

void sample_body(const Scene& scene, std::size_t body_index, Particles& particles) {
  const Body& body = scene.bodies[body_index];
  const Material& material = scene.materials[static_cast<std::size_t>(body.material_index)];
  const double dp = scene.spacing;
  std::vector<Vec2> centres;
  std::vector<double> volumes;
  for_each_sample(body, dp, [&](const Vec2& centre, double volume) {
    centres.push_back(centre);
    volumes.push_back(volume);
  });
  const std::size_t first = particles.size();
  particles.resize(first + centres.size());
  // Axisymmetric: the sample's area A sweeps the ring 2 pi r A about the axis x = 0 (Pappus)
  const bool ring = scene.formulation == Formulation::axisymmetric;
  for (std::size_t k = 0; k < centres.size(); ++k) {
    const std::size_t p = first + k;
    const double volume = ring ? 2.0 * std::numbers::pi * centres[k].x() * volumes[k] : volumes[k];
    particles.position[p] = centres[k];
    particles.velocity[p] = body.initial_velocity;
    particles.displacement[p] = Vec2::Zero();
    particles.volume[p] = volume;
    particles.mass[p] = material.density * volume;
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
