#pragma once
// Velocity of a no-slip dummy particle extrapolated through the wall (`sph.dummy_velocity =
// "extrapolated"`): Morris, Fox & Zhu (1997) J. Comput. Phys. 136:214-226, the boundary
// treatment for soil of Bui et al. (2008) Int. J. Numer. Anal. Meth. Geomech. 32:1537-1570 (ref
// [18] of Peng 2015, whose section 4.2 simplifies it to v_dummy = v_wall). Neither paper is at
// hand (the excerpt Bui et al. 2013 lacks it), so no equation number is cited here.
//
// Seen from soil particle A at distance d_A in front of the wall, dummy B at d_B behind it gets
// the velocity of the linear profile through A and the wall velocity at the wall,
//   v_B = v_w - (d_B / d_A) (v_A - v_w),
// i.e. v_A - v_B = beta (v_A - v_w) with beta = 1 + d_B / d_A, capped at beta_max = 1.5 so that
// a particle close to the wall does not see an unbounded velocity difference.

#include <algorithm>
#include <cstddef>
#include <limits>

#include "common/tensor.hpp"
#include "sph/walls.hpp"

namespace duet::sph {

/// Bui 2008 (after Morris 1997): the cap on beta = (v_A - v_B) / (v_A - v_w).
inline constexpr double kDummyBetaMax = 1.5;

/// The velocity of dummy B seen from soil particle A: v_w + (1 - beta) (v_A - v_w) with
/// beta = min(beta_max, 1 + d_B / d_A). d_A: A's distance in front of the wall, d_B: B's distance
/// behind it. A particle on or behind the wall (d_A <= 0) gets the cap; a dummy in front of the
/// wall line (d_B < 0, past a corner) counts as on it (beta = 1, v_B = v_w).
inline Vec2 extrapolated_dummy_velocity(const Vec2& v_a, const Vec2& v_w, double d_a, double d_b,
                                        double beta_max = kDummyBetaMax) {
  const double d_behind = d_b > 0.0 ? d_b : 0.0;
  // Morris 1997 / Bui 2008: v_B = v_w - (d_B / d_A)(v_A - v_w), beta = 1 + d_B / d_A <= beta_max
  const double beta = d_behind >= (beta_max - 1.0) * d_a ? beta_max : 1.0 + d_behind / d_a;
  return v_w + (1.0 - beta) * (v_a - v_w);
}

/// The line of the wall segment nearest to a soil particle (distance to the segment, end points
/// included): a point on it, its unit normal into the soil, and the particle's signed distance
/// from it (d_A; positive in front). `wall` tags which wall it belongs to (-1: none yet).
struct WallLine {
  Vec2 point = Vec2::Zero();
  Vec2 normal = Vec2::Zero();
  double distance = 0.0;
  int wall = -1;
};

inline WallLine nearest_wall_line(const WallGeometry& geometry, int wall, const Vec2& x) {
  WallLine line;
  line.wall = wall;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s + 1 < geometry.points.size(); ++s) {
    const Vec2 a = geometry.points[s];
    const Vec2 t = geometry.points[s + 1] - a;
    const double u = std::clamp((x - a).dot(t) / t.squaredNorm(), 0.0, 1.0);
    const double d2 = (x - a - u * t).squaredNorm();
    if (d2 < best) {
      best = d2;
      line.point = a;
      line.normal = geometry.normals[s];
    }
  }
  line.distance = (x - line.point).dot(line.normal);
  return line;
}

/// The distance of dummy x_b behind a wall line (d_B; positive behind).
inline double distance_behind(const WallLine& line, const Vec2& x_b) {
  return (line.point - x_b).dot(line.normal);
}

}  // namespace duet::sph
