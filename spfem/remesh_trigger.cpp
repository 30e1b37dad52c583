#include "spfem/remesh_trigger.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>

namespace duet::spfem {
namespace {

// Below this many triangles a loop runs on one thread (as in spfem/smoothing.cpp).
constexpr std::ptrdiff_t kParallelMin = 2048;

constexpr double kDegree = std::numbers::pi / 180.0;

}  // namespace

double arm_remesh_trigger(const AlphaMesh& mesh, const std::vector<Vec2>& points, double angle_deg,
                          double fraction, RemeshTrigger& trigger) {
  const std::ptrdiff_t n = std::ptrdiff_t(mesh.triangles.size());
  trigger.cot_limit.resize(mesh.triangles.size());
  const double infinite = std::numeric_limits<double>::infinity();
  const double plain_cot = angle_deg > 0.0 ? 1.0 / std::tan(angle_deg * kDegree) : infinite;
  if (fraction > 0.0) {
#pragma omp parallel for schedule(static) if (n > kParallelMin)
    for (std::ptrdiff_t e = 0; e < n; ++e) {
      const AngleSides s = smallest_angle_sides(mesh.triangles[std::size_t(e)], points);
      // theta_limit = min(remesh_angle, fraction theta_now); a triangle born flat or inverted
      // (not from a Delaunay mesh) is left to the inversion test
      const double limit =
          s.twice_area > 0.0
              ? std::min(angle_deg * kDegree, fraction * std::atan2(s.twice_area, s.along))
              : 0.0;
      trigger.cot_limit[std::size_t(e)] = limit > 0.0 ? 1.0 / std::tan(limit) : infinite;
    }
  } else {
    std::fill(trigger.cot_limit.begin(), trigger.cot_limit.end(), plain_cot);
  }
  return smallest_angle(mesh, points);
}

bool remesh_due(const AlphaMesh& mesh, const std::vector<Vec2>& points,
                const RemeshTrigger& trigger, double& smallest) {
  const std::ptrdiff_t n = std::ptrdiff_t(mesh.triangles.size());
  const double infinite = std::numeric_limits<double>::infinity();
  double largest_cot = -infinite;
  double inverted = 180.0;
  int due = 0;
#pragma omp parallel for schedule(static) reduction(max                                  \
                                                    : largest_cot) reduction(min         \
                                                                             : inverted) \
    reduction(max                                                                        \
              : due) if (n > kParallelMin)
  for (std::ptrdiff_t e = 0; e < n; ++e) {
    const AngleSides s = smallest_angle_sides(mesh.triangles[std::size_t(e)], points);
    if (s.twice_area > 0.0) {
      // theta < theta_limit  <=>  cot theta > cot theta_limit (0 < theta <= 60 deg)
      const double cot = s.along / s.twice_area;
      largest_cot = std::max(largest_cot, cot);
      if (cot > trigger.cot_limit[std::size_t(e)]) due = 1;
    } else {
      inverted = std::min(inverted, std::atan2(s.twice_area, s.along) / kDegree);
      if (s.twice_area < 0.0 || std::isfinite(trigger.cot_limit[std::size_t(e)])) due = 1;
    }
  }
  // as smallest_angle(): the counter-clockwise triangles by their largest cotangent, an inverted
  // one by its (negative) angle
  const double ccw = largest_cot > -infinite ? std::atan2(1.0, largest_cot) / kDegree : 180.0;
  smallest = std::min(ccw, inverted);
  return due != 0;
}

}  // namespace duet::spfem
