#include "common/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace duet {

namespace {

double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Characteristic size of a polygon (its bounding-box diagonal), for relative tolerances.
double size_of(std::span<const Vec2> polygon) {
  Vec2 lo, hi;
  bounding_box(polygon, lo, hi);
  return (hi - lo).norm();
}

/// Inside and farther than `margin` from the boundary.
bool strictly_inside(const Vec2& p, std::span<const Vec2> polygon, double margin) {
  return point_in_polygon(p, polygon) && polygon_boundary_distance(p, polygon) > margin;
}

bool any_vertex_or_edge_point_inside(std::span<const Vec2> a, std::span<const Vec2> b) {
  const double margin = 1e-9 * std::max(size_of(a), size_of(b));
  const std::size_t n = a.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (strictly_inside(a[i], b, margin)) return true;
    // A point just inside a's edge midpoint (a is counter-clockwise: inside is to the left).
    const Vec2 edge = a[(i + 1) % n] - a[i];
    const double length = edge.norm();
    if (length == 0.0) continue;
    const Vec2 inward(-edge.y() / length, edge.x() / length);
    const Vec2 probe = 0.5 * (a[i] + a[(i + 1) % n]) + 1e-6 * length * inward;
    if (strictly_inside(probe, b, 1e-7 * length)) return true;
  }
  return false;
}

}  // namespace

double signed_area(std::span<const Vec2> polygon) {
  double twice = 0.0;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) twice += cross(polygon[i], polygon[(i + 1) % n]);
  return 0.5 * twice;
}

void make_counter_clockwise(std::vector<Vec2>& polygon) {
  if (signed_area(polygon) < 0.0) std::reverse(polygon.begin(), polygon.end());
}

bool point_in_polygon(const Vec2& point, std::span<const Vec2> polygon) {
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& pi = polygon[i];
    const Vec2& pj = polygon[j];
    if ((pi.y() > point.y()) != (pj.y() > point.y())) {
      const double x_cross = pj.x() + (point.y() - pj.y()) * (pi.x() - pj.x()) / (pi.y() - pj.y());
      if (point.x() < x_cross) inside = !inside;
    }
  }
  return inside;
}

double segment_distance(const Vec2& point, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double length2 = ab.squaredNorm();
  if (length2 == 0.0) return (point - a).norm();
  const double s = std::clamp((point - a).dot(ab) / length2, 0.0, 1.0);
  return (point - (a + s * ab)).norm();
}

double polyline_distance(const Vec2& point, std::span<const Vec2> polyline) {
  if (polyline.size() == 1) return (point - polyline[0]).norm();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
    best = std::min(best, segment_distance(point, polyline[i], polyline[i + 1]));
  }
  return best;
}

double polygon_boundary_distance(const Vec2& point, std::span<const Vec2> polygon) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    best = std::min(best, segment_distance(point, polygon[i], polygon[(i + 1) % n]));
  }
  return best;
}

bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double scale = std::max({(b - a).norm(), (d - c).norm(), 1e-300});
  const double eps = 1e-12 * scale * scale;
  const double d1 = cross(b - a, c - a);
  const double d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c);
  const double d4 = cross(d - c, b - c);
  return ((d1 > eps && d2 < -eps) || (d1 < -eps && d2 > eps)) &&
         ((d3 > eps && d4 < -eps) || (d3 < -eps && d4 > eps));
}

bool path_crosses_polyline(const Vec2& a, const Vec2& b, std::span<const Vec2> points) {
  for (std::size_t s = 0; s + 1 < points.size(); ++s) {
    if (segments_cross(a, b, points[s], points[s + 1])) return true;
  }
  const Vec2 ab = b - a;
  const double length2 = ab.squaredNorm();
  if (!(length2 > 0.0)) return false;
  for (std::size_t v = 1; v + 1 < points.size(); ++v) {
    const Vec2& p = points[v];
    const double scale = std::max(length2, (points[v + 1] - points[v - 1]).squaredNorm());
    // p on the path, strictly between its ends
    if (std::abs(cross(ab, p - a)) > 1e-12 * scale) continue;
    const double u = (p - a).dot(ab) / length2;
    if (!(u > 1e-12 && u < 1.0 - 1e-12)) continue;
    // The ends on opposite sides of the polyline at the vertex: left of it means left of both
    // segments' lines where it turns left, of either where it turns right.
    const Vec2 d1 = p - points[v - 1];
    const Vec2 d2 = points[v + 1] - p;
    const bool left_turn = cross(d1, d2) >= 0.0;
    const auto side = [&](const Vec2& x) {  // +1 left, -1 right, 0 on a line
      const double c1 = cross(d1, x - points[v - 1]);
      const double c2 = cross(d2, x - p);
      const bool left = left_turn ? (c1 > 0.0 && c2 > 0.0) : (c1 > 0.0 || c2 > 0.0);
      const bool right = left_turn ? (c1 < 0.0 || c2 < 0.0) : (c1 < 0.0 && c2 < 0.0);
      return left && !right ? 1 : (right && !left ? -1 : 0);
    };
    if (side(a) * side(b) < 0) return true;
  }
  return false;
}

bool polygons_overlap(std::span<const Vec2> a, std::span<const Vec2> b) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (segments_cross(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()])) return true;
    }
  }
  return any_vertex_or_edge_point_inside(a, b) || any_vertex_or_edge_point_inside(b, a);
}

bool is_simple_polygon(std::span<const Vec2> polygon) {
  const std::size_t n = polygon.size();
  if (n < 3) return false;
  const double tolerance = 1e-12 * size_of(polygon);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % n];
    if ((b - a).norm() <= tolerance) return false;  // repeated vertex
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      const Vec2& c = polygon[j];
      const Vec2& d = polygon[(j + 1) % n];
      if (segments_cross(a, b, c, d)) return false;
      // Touching: an end of one edge on the other.
      if (segment_distance(c, a, b) <= tolerance || segment_distance(d, a, b) <= tolerance ||
          segment_distance(a, c, d) <= tolerance || segment_distance(b, c, d) <= tolerance) {
        return false;
      }
    }
  }
  return true;
}

double polyline_length(std::span<const Vec2> polyline) {
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
    length += (polyline[i + 1] - polyline[i]).norm();
  }
  return length;
}

void bounding_box(std::span<const Vec2> points, Vec2& min, Vec2& max) {
  const double inf = std::numeric_limits<double>::infinity();
  min = Vec2(inf, inf);
  max = Vec2(-inf, -inf);
  for (const Vec2& p : points) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
}

Vec2 schedule_value(const Schedule& schedule, double t) {
  if (schedule.empty()) return Vec2::Zero();
  if (t < schedule.front().time) return schedule.front().value;
  for (std::size_t i = schedule.size() - 1; i > 0; --i) {
    const Knot& lo = schedule[i - 1];
    const Knot& hi = schedule[i];
    if (t >= hi.time) return hi.value;
    if (t >= lo.time) {
      const double s = (t - lo.time) / (hi.time - lo.time);
      return (1.0 - s) * lo.value + s * hi.value;
    }
  }
  return schedule.front().value;
}

Vec2 schedule_integral(const Schedule& schedule, double t) {
  if (schedule.empty() || t <= 0.0) return Vec2::Zero();
  // Exact for a piecewise-linear integrand: the integral over [lo, hi] of each piece.
  auto piece = [&](double lo, double hi, const Knot& a, const Knot& b) -> Vec2 {
    lo = std::max(lo, 0.0);
    hi = std::min(hi, t);
    if (hi <= lo) return Vec2::Zero();
    auto at = [&](double s) {
      return b.time > a.time ? a.value + (s - a.time) / (b.time - a.time) * (b.value - a.value)
                             : a.value;
    };
    return 0.5 * (hi - lo) * (at(lo) + at(hi));
  };
  const Knot& first = schedule.front();
  const Knot& last = schedule.back();
  const double inf = std::numeric_limits<double>::infinity();
  Vec2 sum = piece(-inf, first.time, first, first);
  for (std::size_t i = 1; i < schedule.size(); ++i) {
    sum += piece(schedule[i - 1].time, schedule[i].time, schedule[i - 1], schedule[i]);
  }
  return sum + piece(last.time, inf, last, last);
}

Vec2 radial_displacement(const Vec2& point, const Vec2& centre, double growth) {
  const Vec2 r = point - centre;
  const double length = r.norm();
  return length > 0.0 ? Vec2(growth * r / length) : Vec2(Vec2::Zero());
}

Vec2 moved_along_radius(const Vec2& point, const Vec2& centre, double growth) {
  return point + radial_displacement(point, centre, growth);
}

void fill_sides_from_neighbours(std::vector<int>& side) {
  const std::vector<int> counted = side;
  for (std::size_t s = 0; s < side.size(); ++s) {
    if (counted[s] != 0) continue;
    for (std::size_t k = 1; k < side.size() && side[s] == 0; ++k) {
      if (s >= k && counted[s - k] != 0) side[s] = counted[s - k];
      if (side[s] == 0 && s + k < side.size() && counted[s + k] != 0) side[s] = counted[s + k];
    }
    if (side[s] == 0) side[s] = 1;
  }
}

std::vector<Vec2> wall_points_at(const Wall& wall, double t) {
  std::vector<Vec2> points = wall.points;
  if (wall.radial) {
    const double growth = schedule_integral(wall.radial_velocity, t).x();
    for (Vec2& p : points) p = moved_along_radius(p, wall.centre, growth);
  } else {
    const Vec2 shift = schedule_integral(wall.velocity, t);
    for (Vec2& p : points) p += shift;
  }
  return points;
}

}  // namespace duet
