#include "common/frame_geometry.hpp"

#include <algorithm>

#include "common/geometry.hpp"

namespace duet {

namespace {

void add_polyline(BoundaryLines& lines, const std::vector<Vec2>& points, bool close,
                  std::int32_t owner) {
  const auto first = static_cast<std::int32_t>(lines.points.size());
  lines.points.insert(lines.points.end(), points.begin(), points.end());
  const auto n = static_cast<std::int32_t>(points.size());
  for (std::int32_t k = 0; k + 1 < n; ++k) {
    lines.segments.push_back({first + k, first + k + 1});
    lines.owner.push_back(owner);
  }
  if (close && n > 2) {
    lines.segments.push_back({first + n - 1, first});
    lines.owner.push_back(owner);
  }
}

}  // namespace

BoundaryLines boundary_lines_at(const Scene& scene, double t) {
  const double at = std::max(t, 0.0);
  BoundaryLines lines;
  std::int32_t owner = 0;
  for (const Wall& wall : scene.walls)
    add_polyline(lines, wall_points_at(wall, at), false, owner++);
  for (const RigidBody& body : scene.rigid_bodies) {
    const Vec2 shift = schedule_integral(body.velocity, at);
    std::vector<Vec2> outline = body.outline;
    for (Vec2& p : outline) p += shift;
    add_polyline(lines, outline, true, owner++);
  }
  return lines;
}

std::vector<MeshEdge> surface_edges(const std::vector<MeshTriangle>& triangles) {
  // Every edge as (low, high, as oriented), sorted: an edge of one triangle appears once.
  struct Edge {
    std::int32_t low, high;
    MeshEdge oriented;
  };
  std::vector<Edge> edges;
  edges.reserve(3 * triangles.size());
  for (const MeshTriangle& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = t[k], b = t[(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), {a, b}});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
    return x.low != y.low ? x.low < y.low : x.high < y.high;
  });
  std::vector<MeshEdge> out;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].low == edges[i].low && edges[j].high == edges[i].high) ++j;
    if (j - i == 1) out.push_back(edges[i].oriented);
    i = j;
  }
  return out;
}

}  // namespace duet
