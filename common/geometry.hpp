#pragma once
// Plane geometry for scenes: polygon area and orientation, point in polygon, distance to a
// segment, polygon overlap, polylines, and piecewise-linear schedules (walls, rigid bodies, loads).
// Polygons are lists of vertices without repeating the first one.

#include <span>
#include <vector>

#include "common/scene.hpp"
#include "common/tensor.hpp"

namespace duet {

/// Signed area (shoelace formula): positive for a counter-clockwise polygon.
double signed_area(std::span<const Vec2> polygon);

/// Reverses a clockwise polygon so it runs counter-clockwise.
void make_counter_clockwise(std::vector<Vec2>& polygon);

/// Crossing-number test. Points on an edge are resolved by the half-open rule (an edge owns its
/// lower end, and a point exactly on a left edge is inside, on a right edge outside), so a lattice
/// of cells covering a plane is shared out between polygons that tile it without double counting.
bool point_in_polygon(const Vec2& point, std::span<const Vec2> polygon);

/// Euclidean distance from `point` to the segment [a, b].
double segment_distance(const Vec2& point, const Vec2& a, const Vec2& b);

/// Smallest distance from `point` to any segment of an open polyline.
double polyline_distance(const Vec2& point, std::span<const Vec2> polyline);

/// Smallest distance from `point` to the boundary of a polygon.
double polygon_boundary_distance(const Vec2& point, std::span<const Vec2> polygon);

/// True when the segments [a, b] and [c, d] cross at a single point interior to both (touching
/// at an end or running along each other does not count).
bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d);

/// True when the path [a, b] crosses the open polyline `points`: it crosses a segment at a point
/// interior to both, or it passes through an interior vertex with its ends on opposite sides of
/// the polyline there (a particle sliding through a chorded wall exactly at a vertex, which
/// segments_cross counts for neither segment).
bool path_crosses_polyline(const Vec2& a, const Vec2& b, std::span<const Vec2> points);

/// True when the interiors of two simple polygons overlap with positive area. Polygons that only
/// touch along edges or at vertices do not overlap. Test: some pair of edges crosses properly, or
/// a vertex of one, or a point just inside an edge midpoint of one, lies strictly inside the
/// other (this catches containment and coincident outlines, where no edges cross).
bool polygons_overlap(std::span<const Vec2> a, std::span<const Vec2> b);

/// True when no two non-adjacent edges of the polygon cross or touch.
bool is_simple_polygon(std::span<const Vec2> polygon);

/// Total length of an open polyline.
double polyline_length(std::span<const Vec2> polyline);

/// Axis-aligned bounding box of points.
void bounding_box(std::span<const Vec2> points, Vec2& min, Vec2& max);

/// Value of a piecewise-linear schedule at time t (constant outside the knots; zero if empty).
/// Where two knots share a time the later one wins (a jump).
Vec2 schedule_value(const Schedule& schedule, double t);

/// Integral of the schedule from 0 to t (the displacement of a wall moving with it).
Vec2 schedule_integral(const Schedule& schedule, double t);

/// The displacement of `point` away from `centre` by `growth` along the radius through it (a
/// radial wall's point; zero at the centre itself).
Vec2 radial_displacement(const Vec2& point, const Vec2& centre, double growth);

/// `point` moved by radial_displacement.
Vec2 moved_along_radius(const Vec2& point, const Vec2& centre, double growth);

/// Per segment of a wall, the side its material lies on (+1 / -1), where 0 marks a segment that
/// no material point projects onto: each such segment takes the side of the nearest segment along
/// the wall that has one (the first found walking out both ways, the earlier on a tie), +1 when
/// none has. Left to a default, the short chords of a curved wall (the cavity's 16 at dp 0.5)
/// faced away from the soil, in espfem's node contact and in SPH's walls alike.
void fill_sides_from_neighbours(std::vector<int>& side);

/// A wall's polyline at time t: translated by the integral of its velocity or, for a radial
/// wall, every point moved away from the centre by the integral of the radial speed.
std::vector<Vec2> wall_points_at(const Wall& wall, double t);

}  // namespace duet
