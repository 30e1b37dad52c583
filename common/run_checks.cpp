#include "common/run_checks.hpp"

#include <cmath>

#include "common/geometry.hpp"

namespace duet {

StateChecks::StateChecks(const Scene& scene) : scene_(scene) {}

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
  // translating wall moved by its own displacement), properly crosses a wall segment.
  for (const Wall& wall : scene_.walls) {
    const std::vector<Vec2> points = wall_points_at(wall, time);
    const Vec2 wall_motion = wall.radial ? Vec2::Zero()
                                         : Vec2(schedule_integral(wall.velocity, time) -
                                                schedule_integral(wall.velocity, previous_time));
    Vec2 lo, hi;
    bounding_box(points, lo, hi);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 from = previous_position[i] + wall_motion;
      const Vec2& to = particles.position[i];
      if ((from.array().max(to.array()) < lo.array()).any() ||
          (from.array().min(to.array()) > hi.array()).any()) {
        continue;
      }
      for (std::size_t s = 0; s + 1 < points.size(); ++s) {
        if (segments_cross(from, to, points[s], points[s + 1])) {
          return StateProblem{
              describe(("particle crossed wall '" + wall.name + "'").c_str(), i, to),
              static_cast<long>(i), to};
        }
      }
    }
  }
  return std::nullopt;
}

}  // namespace duet
