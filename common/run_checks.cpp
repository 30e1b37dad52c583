#include "common/run_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/geometry.hpp"

namespace duet {

namespace {

bool fixed(const Wall& wall) {
  if (wall.radial) return false;
  for (const Knot& k : wall.velocity) {
    if (k.value != Vec2::Zero()) return false;
  }
  return true;
}

}  // namespace

StateChecks::StateChecks(const Scene& scene, const Particles& initial) : scene_(scene) {
  if (scene.checks.lift_off_fraction <= 0.0) return;
  const double reach = scene.spacing * (1.0 + 1e-9);
  for (std::size_t w = 0; w < scene.walls.size(); ++w) {
    const Wall& wall = scene.walls[w];
    if (wall.condition != WallCondition::no_slip || !fixed(wall)) continue;
    Contact contact{w, {}};
    for (std::size_t i = 0; i < initial.size(); ++i) {
      if (polyline_distance(initial.position[i], wall.points) <= reach) {
        contact.particles.push_back(i);
      }
    }
    if (!contact.particles.empty()) contacts_.push_back(std::move(contact));
  }
}

namespace {

std::string describe(const char* what, std::size_t i, const Vec2& x) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "%s at particle %zu (x = %.6g, y = %.6g)", what, i, x.x(),
                x.y());
  return buffer;
}

}  // namespace

std::optional<StateProblem> StateChecks::check(const Particles& particles,
                                               const std::vector<Vec2>& previous_position,
                                               double previous_time, double time) const {
  const std::size_t n = particles.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& x = particles.position[i];
    const char* what = nullptr;
    if (!x.allFinite()) {
      what = "non-finite position";
    } else if (!particles.velocity[i].allFinite()) {
      what = "non-finite velocity";
    } else if (!particles.stress[i].allFinite()) {
      what = "non-finite stress";
    } else if ((x.array() < scene_.domain.min.array()).any() ||
               (x.array() > scene_.domain.max.array()).any()) {
      what = "particle left the domain";
    }
    if (what) return StateProblem{describe(what, i, x), static_cast<long>(i), x};
  }
  // A particle crossing a wall: its path over the step, seen in the frame of the wall (a
  // translating wall moved by its own displacement, a radial wall's point by its growth along
  // the radius), properly crosses a wall segment. Without the radial growth a cavity wall that
  // overtook a slower particle was never seen to cross it (the SPH cavity at dp 0.35: a particle
  // behind the wall from t = 2.4 s on).
  for (const Wall& wall : scene_.walls) {
    const std::vector<Vec2> points = wall_points_at(wall, time);
    const Vec2 wall_motion = wall.radial ? Vec2::Zero()
                                         : Vec2(schedule_integral(wall.velocity, time) -
                                                schedule_integral(wall.velocity, previous_time));
    const double growth = wall.radial
                              ? schedule_integral(wall.radial_velocity, time).x() -
                                    schedule_integral(wall.radial_velocity, previous_time).x()
                              : 0.0;
    Vec2 lo, hi;
    bounding_box(points, lo, hi);
    // A node added during the step (espfem's spfem.wall_node_gap, appended) has no path yet.
    const std::size_t n_before = std::min(n, previous_position.size());
    for (std::size_t i = 0; i < n_before; ++i) {
      const Vec2 from = growth != 0.0
                            ? moved_along_radius(previous_position[i], wall.centre, growth)
                            : Vec2(previous_position[i] + wall_motion);
      const Vec2& to = particles.position[i];
      if ((from.array().max(to.array()) < lo.array()).any() ||
          (from.array().min(to.array()) > hi.array()).any()) {
        continue;
      }
      if (path_crosses_polyline(from, to, points)) {
        return StateProblem{describe(("particle crossed wall '" + wall.name + "'").c_str(), i, to),
                            static_cast<long>(i), to};
      }
    }
  }
  return std::nullopt;
}

std::optional<StateProblem> StateChecks::check_lift_off(const Particles& particles) const {
  const double distance = scene_.checks.lift_off_distance * scene_.spacing;
  for (const Contact& c : contacts_) {
    const Wall& wall = scene_.walls[c.wall];
    std::size_t away = 0;
    double furthest = 0.0;
    std::size_t which = c.particles.front();
    for (std::size_t i : c.particles) {
      const double d = polyline_distance(particles.position[i], wall.points);
      if (d > distance) ++away;
      if (d > furthest) {
        furthest = d;
        which = i;
      }
    }
    const double fraction = static_cast<double>(away) / static_cast<double>(c.particles.size());
    if (fraction > scene_.checks.lift_off_fraction) {
      char buffer[320];
      std::snprintf(buffer, sizeof buffer,
                    "lifted off no-slip wall '%s': %.0f %% of the %zu particles on it at t = 0 "
                    "are more than %g spacings (%g m) from it, up to %.4g m "
                    "(checks.lift_off_fraction = %g)",
                    wall.name.c_str(), 100.0 * fraction, c.particles.size(),
                    scene_.checks.lift_off_distance, distance, furthest,
                    scene_.checks.lift_off_fraction);
      return StateProblem{buffer, static_cast<long>(which), particles.position[which]};
    }
  }
  return std::nullopt;
}

std::optional<std::string> energy_runaway(const RunCheckOptions& options, double kinetic,
                                          const EnergyBudget& budget, const char* unit) {
  if (options.kinetic_energy_factor <= 0.0 || budget.incomplete()) return std::nullopt;
  const double limit = options.kinetic_energy_factor * std::max(budget.input(), 0.0);
  if (kinetic <= limit || kinetic <= budget.floor()) return std::nullopt;
  char buffer[320];
  std::snprintf(buffer, sizeof buffer,
                "kinetic energy %.4g %s exceeds %g x the energy put in (%.4g %s: gravity %.4g, "
                "walls and rigid bodies %.4g, loads %.4g, initial kinetic %.4g, initial elastic "
                "%.4g): the method made energy (checks.kinetic_energy_factor)",
                kinetic, unit, options.kinetic_energy_factor, budget.input(), unit,
                budget.gravity_work(), budget.boundary_work(), budget.load_work(),
                budget.initial_kinetic(), budget.initial_elastic());
  return std::string(buffer);
}

}  // namespace duet
