#include "common/standing_faces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <variant>

#include "common/geometry.hpp"
#include "common/scene_validation.hpp"

namespace duet {

namespace {

/// A cohesionless soil's friction angle (deg) at full strength (before any strength reduction),
/// or nothing where the material has cohesion or no friction angle of its own (elasticity,
/// Tresca, hypoplasticity given by c1..c4). A cohesion not given is the models' default, 0.
std::optional<double> cohesionless_friction(const Material& m) {
  auto number = [&](const char* key) -> std::optional<double> {
    const auto it = m.full_strength.find(key);
    if (it == m.full_strength.end()) return std::nullopt;
    const double* value = std::get_if<double>(&it->second);
    return value ? std::optional<double>(*value) : std::nullopt;
  };
  const std::optional<double> c = number("c");
  if (c && *c != 0.0) return std::nullopt;
  if (m.model == "drucker-prager" || m.model == "mohr-coulomb") return number("phi");
  // Given by c1..c4 its friction angle is implied, below 90 deg: a vertical face cannot stand
  if (m.model == "hypoplastic") return number("phi").value_or(90.0 - 1e-6);
  if (m.model == "simhypo-sand") return number("phi_c");
  return std::nullopt;
}

/// Distance from p to every boundary but the body's own outline: walls, rigid bodies, other bodies.
double distance_to_others(const Scene& scene, std::size_t body, const Vec2& p) {
  double best = distance_to_walls(scene, p);
  for (std::size_t k = 0; k < scene.bodies.size(); ++k) {
    if (k != body) best = std::min(best, polygon_boundary_distance(p, scene.bodies[k].outline));
  }
  return best;
}

}  // namespace

std::string face_steeper_than_friction(const Scene& scene) {
  if (scene.gravity.norm() == 0.0) return "";
  const Vec2 down = scene.gravity.normalized();
  const double reach = scene.spacing * (1.0 + 1e-9);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Body& b = scene.bodies[i];
    const Material& m = scene.materials[static_cast<std::size_t>(b.material_index)];
    const std::optional<double> phi = cohesionless_friction(m);
    if (!phi) continue;
    const std::size_t n = b.outline.size();
    for (std::size_t e = 0; e < n; ++e) {
      const Vec2& a = b.outline[e];
      const Vec2& c = b.outline[(e + 1) % n];
      const double length = (c - a).norm();
      if (!(length > scene.spacing)) continue;  // a chamfer below the resolution
      const double angle =
          std::asin(std::min(1.0, std::abs((c - a).dot(down)) / length)) * 180.0 / std::numbers::pi;
      if (angle <= *phi + 1e-9) continue;
      // Free: its quarter, middle and three-quarter points all away from every other boundary
      bool free = true;
      for (const double s : {0.25, 0.5, 0.75}) {
        free = free && distance_to_others(scene, i, a + s * (c - a)) > reach;
      }
      if (!free) continue;
      std::ostringstream why;
      why.precision(4);
      why << "body." << b.name << ": its side (" << a.x() << ", " << a.y() << ") - (" << c.x()
          << ", " << c.y() << ") is a free face at " << angle << " deg to the horizontal in "
          << m.model << " soil '" << m.name << "' with phi " << (*phi > 89.99 ? "below " : "= ")
          << (*phi > 89.99 ? 90.0 : *phi)
          << " deg and no cohesion: no dry slope stands steeper than phi, so there is no static "
             "equilibrium for a quasi-static method to find (the collapse is dynamic)";
      return why.str();
    }
  }
  return "";
}

}  // namespace duet
