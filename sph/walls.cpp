#include "sph/walls.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/geometry.hpp"

namespace duet::sph {

namespace {

Vec2 left_normal(const Vec2& a, const Vec2& b) {
  const Vec2 t = (b - a).normalized();
  return Vec2(-t.y(), t.x());
}

/// A closed outline (its last point repeats its first): a rigid body's.
bool closed_outline(const std::vector<Vec2>& points) {
  return points.size() >= 4 && points.front() == points.back();
}

/// Whether x lies within dp/2 of one of `points` (a dummy already laid there).
bool near_any(std::span<const Vec2> points, const Vec2& x, double dp) {
  return std::any_of(points.begin(), points.end(),
                     [&](const Vec2& y) { return (y - x).squaredNorm() < 0.25 * dp * dp; });
}

/// Calls visit(segment, along, x) for the points of `layers` rows at (k - 1/2) dp behind every
/// segment, spaced dp along it and extended by layers * dp past its ends; `along` is the
/// distance from the segment's start. Rows start half a spacing in from each end so soil sampled
/// on the same lattice lines up.
template <class Visit>
void for_each_row_point(const WallGeometry& wall, double dp, int layers, Visit visit) {
  const double extension = layers * dp;
  for (std::size_t s = 0; s + 1 < wall.points.size(); ++s) {
    const Vec2 a = wall.points[s];
    const Vec2 b = wall.points[s + 1];
    const Vec2 t = (b - a).normalized();
    const double length = (b - a).norm();
    const int n_along = static_cast<int>(std::floor((length + 2.0 * extension) / dp + 1e-9));
    const double start = -extension + 0.5 * ((length + 2.0 * extension) - n_along * dp) + 0.5 * dp;
    for (int k = 1; k <= layers; ++k) {
      for (int m = 0; m < n_along; ++m) {
        const double along = start + m * dp;
        visit(s, along, Vec2(a + along * t - (k - 0.5) * dp * wall.normals[s]));
      }
    }
  }
}

}  // namespace

WallGeometry orient_wall(const WallSpec& wall, std::span<const Vec2> soil, double reach) {
  if (wall.polyline.size() < 2) {
    throw std::invalid_argument("wall " + wall.name + ": a polyline needs at least two points");
  }
  WallGeometry geometry;
  geometry.points = wall.polyline;
  for (std::size_t s = 0; s + 1 < geometry.points.size(); ++s) {
    const Vec2 a = geometry.points[s];
    const Vec2 b = geometry.points[s + 1];
    if ((b - a).norm() <= 0.0) {
      throw std::invalid_argument("wall " + wall.name + ": repeated point in polyline");
    }
    const Vec2 n = left_normal(a, b);
    const Vec2 t = (b - a).normalized();
    const double length = (b - a).norm();
    int left = 0;
    int right = 0;
    for (const Vec2& x : soil) {
      const double u = (x - a).dot(t);
      const double d = (x - a).dot(n);
      if (u < 0.0 || u > length || std::abs(d) > reach) continue;
      (d >= 0.0 ? left : right) += 1;
    }
    geometry.side.push_back(left + right == 0 ? 0 : right > left ? -1 : 1);  // 0: no soil, below
  }
  // An open wall's segment that no soil particle projects onto takes the side of the nearest one
  // along the wall that some do (fill_sides_from_neighbours). Left to the left normal, the
  // cavity's chords that no particle projects onto within reach (10 of its 16 at dp 0.5, 8 at
  // 0.35, none at 0.25) faced the cavity, held no ghost of the soil in front of them, and the
  // expanding wall overtook the soil. A closed outline (a rigid body) has the soil outside it:
  // every normal points out of the polygon. Counted, the footing (0.3 m thick, thinner than the
  // reach) saw the soil below it from its top and its sides took the left normal: three of its
  // four sides faced into it and every row of its dummies lay outside it (benchmarks/RESULTS.md,
  // "SPH's walls facing the wrong way").
  const std::vector<Vec2>& p = geometry.points;
  const bool closed = closed_outline(p);
  if (closed) {
    const double area = signed_area(std::span<const Vec2>(p.data(), p.size() - 1));
    geometry.side.assign(p.size() - 1, area > 0.0 ? -1 : 1);  // counter-clockwise: the right
  } else {
    fill_sides_from_neighbours(geometry.side);
  }
  geometry.normals.resize(geometry.side.size());
  update_normals(geometry);  // side x left normal, as after every move
  if (closed) {
    // Which faces have soil in front of them: those get their dummy rows at full depth even where
    // the body is thinner (dummy_particles).
    geometry.faces_soil.assign(geometry.side.size(), 0);
    for (std::size_t s = 0; s < geometry.side.size(); ++s) {
      for (const Vec2& x : soil) {
        bool inside = false;
        const double d = signed_distance(geometry, s, x, &inside);
        if (inside && d >= 0.0 && d <= reach) {
          geometry.faces_soil[s] = 1;
          break;
        }
      }
    }
  }
  geometry.point_velocity.assign(geometry.points.size(), Vec2::Zero());
  return geometry;
}

void update_normals(WallGeometry& wall) {
  for (std::size_t s = 0; s + 1 < wall.points.size(); ++s) {
    wall.normals[s] = wall.side[s] * left_normal(wall.points[s], wall.points[s + 1]);
  }
}

double signed_distance(const WallGeometry& wall, std::size_t segment, const Vec2& x,
                       bool* projects_inside) {
  const Vec2 a = wall.points[segment];
  const Vec2 b = wall.points[segment + 1];
  if (projects_inside) {
    const Vec2 t = b - a;
    const double u = (x - a).dot(t) / t.squaredNorm();
    *projects_inside = u >= 0.0 && u <= 1.0;
  }
  return (x - a).dot(wall.normals[segment]);
}

namespace {

/// A rigid body's dummies (a closed outline, normals out of it): every row point inside the body,
/// and, behind a face with soil in front of it, the rows to their full depth where the body is
/// thinner than the layers (the footing, 0.3 m thick, holds one row of three at dp 0.25: the soil
/// under it saw a third of the support it needs). Rows stop at the face's ends, so the body is not
/// widened beyond a convex corner, and a thickening point is dropped in front of another face
/// with soil before it.
std::vector<Vec2> body_dummies(const WallGeometry& body, double dp, int layers) {
  std::vector<Vec2> out;
  const std::span<const Vec2> polygon(body.points.data(), body.points.size() - 1);
  const double extension = layers * dp;
  for_each_row_point(body, dp, layers, [&](std::size_t s, double along, const Vec2& x) {
    const double length = (body.points[s + 1] - body.points[s]).norm();
    bool keep = point_in_polygon(x, polygon);
    if (!keep && body.faces_soil[s] != 0 && along >= 0.0 && along <= length) {
      keep = true;
      for (std::size_t o = 0; o + 1 < body.points.size() && keep; ++o) {
        bool inside = false;
        const double d = signed_distance(body, o, x, &inside);
        if (o != s && body.faces_soil[o] != 0 && inside && d > 0.0 && d < extension) keep = false;
      }
    }
    if (keep && !near_any(out, x, dp)) out.push_back(x);
  });
  return out;
}

}  // namespace

std::vector<Vec2> dummy_particles(const WallGeometry& wall, double dp, int layers) {
  if (!wall.faces_soil.empty()) return body_dummies(wall, dp, layers);
  std::vector<Vec2> out;
  const double extension = layers * dp;
  for_each_row_point(wall, dp, layers, [&](std::size_t, double, const Vec2& x) {
    // A corner point behind one segment may be in front of its neighbour: keep only points that
    // are behind (or level with) every segment they project onto.
    for (std::size_t o = 0; o + 1 < wall.points.size(); ++o) {
      bool inside = false;
      const double d = signed_distance(wall, o, x, &inside);
      if (inside && d > 0.0 && d < extension) return;
    }
    if (!near_any(out, x, dp)) out.push_back(x);
  });
  return out;
}

std::vector<Vec2> mirror_dummies_across(const WallGeometry& plane, std::span<const Vec2> dummies,
                                        double reach, double dp) {
  std::vector<Vec2> out;
  if (plane.points.size() != 2) return out;  // a symmetry plane is one straight segment
  const Vec2 a = plane.points[0];
  const Vec2 n = plane.normals[0];
  for (const Vec2& x : dummies) {
    const double d = (x - a).dot(n);
    if (!(d > 0.0 && d < reach)) continue;
    const Vec2 image = x - 2.0 * d * n;
    if (!near_any(dummies, image, dp) && !near_any(out, image, dp)) out.push_back(image);
  }
  return out;
}

bool behind_wall(const WallGeometry& wall, const Vec2& x, double depth) {
  // A closed outline (a rigid body): inside its polygon. Behind a side within `depth` would count
  // the soil under a body thinner than `depth` as behind its top.
  const std::vector<Vec2>& p = wall.points;
  if (closed_outline(p)) return point_in_polygon(x, std::span<const Vec2>(p.data(), p.size() - 1));
  for (std::size_t s = 0; s + 1 < wall.points.size(); ++s) {
    bool inside = false;
    const double d = signed_distance(wall, s, x, &inside);
    if (inside && d < 0.0 && d > -depth) return true;
  }
  return false;
}

bool mirror_particle(const WallGeometry& wall, std::size_t segment, const Vec2& x, const Vec2& v,
                     double reach, Vec2& x_ghost, Vec2& v_ghost) {
  const Vec2 n = wall.normals[segment];
  const Vec2 a = wall.points[segment];
  const Vec2 t = wall.points[segment + 1] - a;
  const double d = (x - a).dot(n);
  const double u = (x - a).dot(t) / t.squaredNorm();
  const Vec2 v_wall =
      (1.0 - u) * wall.point_velocity[segment] + u * wall.point_velocity[segment + 1];
  // Peng 2015 section 4.2: ghost mirrored across the wall, tangential velocity kept and the
  // normal velocity (relative to the wall) reversed.
  const Vec2 relative = v - v_wall;
  x_ghost = x - 2.0 * d * n;
  v_ghost = v_wall + relative - 2.0 * relative.dot(n) * n;
  return u >= 0.0 && u <= 1.0 && d >= 0.0 && d < reach;
}

std::ptrdiff_t segment_before(const WallGeometry& wall, std::size_t after) {
  if (after > 0) return static_cast<std::ptrdiff_t>(after) - 1;
  return closed_outline(wall.points) ? static_cast<std::ptrdiff_t>(wall.points.size()) - 2 : -1;
}

bool mirror_at_vertex(const WallGeometry& wall, std::size_t after, const Vec2& x, const Vec2& v,
                      double reach, Vec2& x_ghost, Vec2& v_ghost, Vec2& normal) {
  const std::ptrdiff_t before = segment_before(wall, after);
  const Vec2 p = wall.points[after];
  const Vec2 r = x - p;
  const double distance = r.norm();
  normal = distance > 0.0 ? Vec2(r / distance) : wall.normals[after];
  const Vec2 relative = v - wall.point_velocity[after];
  x_ghost = p - r;
  v_ghost = wall.point_velocity[after] + relative - 2.0 * relative.dot(normal) * normal;
  if (before < 0 || !(distance < reach)) return false;
  const auto b = static_cast<std::size_t>(before);
  const Vec2 t_before = wall.points[b + 1] - wall.points[b];
  const Vec2 t_after = wall.points[after + 1] - p;
  // In the wedge: beyond the end of the segment before and the start of the one after, in
  // front of both (only a convex vertex, seen from the soil, has such points)
  return r.dot(t_before) > 0.0 && r.dot(t_after) < 0.0 && r.dot(wall.normals[b]) >= 0.0 &&
         r.dot(wall.normals[after]) >= 0.0;
}

}  // namespace duet::sph
