#include "spfem/node_contact.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/geometry.hpp"

namespace duet::spfem {

namespace {

Vec2 left_normal(const Vec2& a, const Vec2& b) {
  const Vec2 t = (b - a).normalized();
  return Vec2(-t.y(), t.x());
}

/// Velocity of the boundary point x at time t.
Vec2 point_velocity(const NodeBoundary& boundary, double t, const Vec2& x) {
  if (boundary.radial) {
    const Vec2 r = x - boundary.centre;
    const double d = r.norm();
    return d > 0.0 ? Vec2(schedule_value(boundary.radial_velocity, t).x() / d * r)
                   : Vec2(Vec2::Zero());
  }
  return schedule_value(boundary.velocity, t);
}

}  // namespace

void update_geometry(const NodeBoundary& boundary, double t, BoundaryGeometry& geometry) {
  geometry.points = boundary.polyline;
  if (boundary.radial) {
    const double growth = schedule_integral(boundary.radial_velocity, t).x();
    for (Vec2& p : geometry.points) {
      const Vec2 r = p - boundary.centre;
      const double length = r.norm();
      if (length > 0.0) p += growth * r / length;
    }
  } else {
    const Vec2 shift = schedule_integral(boundary.velocity, t);
    for (Vec2& p : geometry.points) p += shift;
  }
  geometry.point_velocity.resize(geometry.points.size());
  for (std::size_t k = 0; k < geometry.points.size(); ++k) {
    geometry.point_velocity[k] = point_velocity(boundary, t, geometry.points[k]);
  }
  geometry.normals.resize(geometry.side.size());
  for (std::size_t s = 0; s < geometry.side.size(); ++s) {
    geometry.normals[s] =
        geometry.side[s] * left_normal(geometry.points[s], geometry.points[s + 1]);
  }
}

BoundaryGeometry orient_boundary(const NodeBoundary& boundary, std::span<const Vec2> nodes,
                                 double reach) {
  if (boundary.polyline.size() < 2) {
    throw std::invalid_argument(boundary.name + ": a boundary needs at least two points");
  }
  BoundaryGeometry geometry;
  const std::vector<Vec2>& p = boundary.polyline;
  for (std::size_t s = 0; s + 1 < p.size(); ++s) {
    const Vec2 a = p[s];
    const Vec2 b = p[s + 1];
    if ((b - a).norm() <= 0.0) {
      throw std::invalid_argument(boundary.name + ": repeated point in its outline");
    }
    if (boundary.rigid_body) {
      // Counter-clockwise outline: the body is on the left, the soil on the right.
      geometry.side.push_back(-1);
      continue;
    }
    const Vec2 n = left_normal(a, b);
    const Vec2 t = (b - a).normalized();
    const double length = (b - a).norm();
    int left = 0;
    int right = 0;
    for (const Vec2& x : nodes) {
      const double u = (x - a).dot(t);
      const double d = (x - a).dot(n);
      if (u < 0.0 || u > length || std::abs(d) > reach) continue;
      (d >= 0.0 ? left : right) += 1;
    }
    geometry.side.push_back(left == right ? 0 : right > left ? -1 : 1);  // 0: no nodes, below
  }
  // Segments with no nodes of their own (left == right): the side of the nearest segment along
  // the wall that has some. Left to the default (+1), the cavity's chords at dp 0.5 faced the
  // cavity, and the expanding wall passed through the soil's first row untouched.
  fill_sides_from_neighbours(geometry.side);
  update_geometry(boundary, 0.0, geometry);
  return geometry;
}

void find_contacts(const BoundaryGeometry& geometry, bool rigid_body, std::int32_t node,
                   std::int32_t boundary, const Vec2& x, double reach, double depth,
                   std::vector<NodeContact>& out) {
  bool projects_on_any = false;
  for (std::size_t s = 0; s + 1 < geometry.points.size(); ++s) {
    const Vec2 a = geometry.points[s];
    const Vec2 b = geometry.points[s + 1];
    const Vec2 ab = b - a;
    const double u = (x - a).dot(ab) / ab.squaredNorm();
    if (u < 0.0 || u > 1.0) continue;
    const double d = (x - a).dot(geometry.normals[s]);
    if (std::abs(d) <= reach) projects_on_any = true;
    if (d > reach || d < -depth) continue;
    const Vec2 v = (1.0 - u) * geometry.point_velocity[s] + u * geometry.point_velocity[s + 1];
    out.push_back({node, boundary, geometry.normals[s], d, v, a + u * ab});
  }
  if (!rigid_body || projects_on_any) return;
  // A convex corner of a rigid body: the node lies in the fan between two segment normals.
  for (std::size_t k = 0; k + 1 < geometry.points.size(); ++k) {
    const Vec2 r = x - geometry.points[k];
    const double d = r.norm();
    if (d > reach || d <= 0.0) continue;
    out.push_back({node, boundary, r / d, d, geometry.point_velocity[k], geometry.points[k]});
  }
}

std::int64_t first_node_crossing(const BoundaryGeometry& wall_at_end, const Vec2& wall_motion,
                                 std::span<const Vec2> x, std::span<const Vec2> u) {
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (path_crosses_polyline(x[i] + wall_motion, x[i] + u[i], wall_at_end.points)) {
      return static_cast<std::int64_t>(i);
    }
  }
  return -1;
}

bool touch_wall_vertex(const BoundaryGeometry& geometry, std::int32_t node, std::int32_t boundary,
                       const Vec2& x, double reach, NodeContact& out) {
  const std::vector<Vec2>& p = geometry.points;
  for (std::size_t v = 1; v + 1 < p.size(); ++v) {
    const Vec2 d = x - p[v];
    const double distance = d.norm();
    if (!(distance > 0.0) || distance > reach) continue;
    // in the fan: past the end of segment v - 1, before the start of segment v, soil side of both
    if (d.dot(p[v] - p[v - 1]) < 0.0 || d.dot(p[v + 1] - p[v]) > 0.0) continue;
    if (d.dot(geometry.normals[v - 1]) <= 0.0 || d.dot(geometry.normals[v]) <= 0.0) continue;
    out = {node, boundary, d / distance, distance, geometry.point_velocity[v], p[v]};
    return true;
  }
  return false;
}

void find_node_contacts(const BoundaryGeometry& geometry, bool rigid_body, std::int32_t node,
                        std::int32_t boundary, const Vec2& x, double reach, double depth,
                        std::vector<NodeContact>& out) {
  const std::size_t before = out.size();
  find_contacts(geometry, rigid_body, node, boundary, x, reach, depth, out);
  NodeContact vertex;
  if (out.size() == before && !rigid_body &&
      touch_wall_vertex(geometry, node, boundary, x, reach, vertex)) {
    out.push_back(vertex);  // a wall's convex vertex (the cavity's chords)
  }
}

bool project_on_boundary(const BoundaryGeometry& geometry, std::int32_t node, std::int32_t boundary,
                         const Vec2& x, double depth, double max_distance, NodeContact& out) {
  bool found = false;
  for (std::size_t s = 0; s + 1 < geometry.points.size(); ++s) {
    const Vec2 a = geometry.points[s];
    const Vec2 ab = geometry.points[s + 1] - a;
    const double u = (x - a).dot(ab) / ab.squaredNorm();
    if (u < 0.0 || u > 1.0) continue;
    const double d = (x - a).dot(geometry.normals[s]);
    if (d > max_distance || d < -depth) continue;
    if (found && std::abs(d) >= std::abs(out.distance)) continue;
    const Vec2 v = (1.0 - u) * geometry.point_velocity[s] + u * geometry.point_velocity[s + 1];
    out = {node, boundary, geometry.normals[s], d, v, a + u * ab};
    found = true;
  }
  return found;
}

Vec2 constrain_velocity(const NodeContact& contact, NodeCondition condition, double friction,
                        Vec2& velocity) {
  const Vec2 before = velocity;
  const Vec2& n = contact.normal;
  const Vec2 relative = velocity - contact.boundary_velocity;
  const double approach = relative.dot(n);  // < 0: moving into the boundary
  switch (condition) {
    case NodeCondition::bonded:
      velocity = contact.boundary_velocity;
      break;
    case NodeCondition::rough:
      if (approach < 0.0) velocity = contact.boundary_velocity;
      break;
    case NodeCondition::smooth:
      if (approach < 0.0) velocity -= approach * n;
      break;
    case NodeCondition::symmetry:  // the mirror image holds the node both ways
      velocity -= approach * n;
      break;
    case NodeCondition::friction: {
      if (approach >= 0.0) break;
      velocity -= approach * n;
      // Coulomb: the tangential velocity change is capped by mu times the normal one.
      const Vec2 tangential = relative - approach * n;
      const double slip = tangential.norm();
      const double cap = friction * (-approach);
      if (slip <= cap) {
        velocity -= tangential;
      } else if (slip > 0.0) {
        velocity -= cap / slip * tangential;
      }
      break;
    }
  }
  return velocity - before;
}

}  // namespace duet::spfem
