#pragma once
// Wall treatment of the SPH solver (Peng 2015 section 4.2): walls are polylines; a no-slip wall
// is represented by layers of dummy particles behind it (three by default) that move with the
// wall's prescribed velocity; a free-slip wall by ghost particles, the mirror images of the soil
// particles within 2h of it, with the normal velocity reversed. Which side of a wall segment is
// the soil side is found once, from the soil particles near the segment.

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "common/scene.hpp"
#include "common/tensor.hpp"

namespace duet::sph {

/// Prescribed velocity (m/s) of the wall point x at time t: a translation ignores x, a radially
/// expanding wall (cavity) points away from its centre.
using WallVelocity = std::function<Vec2(double t, const Vec2& x)>;

/// A wall or rigid body boundary as the solver sees it.
struct WallSpec {
  std::string name;
  std::vector<Vec2> polyline;  // m; >= 2 points; a closed outline repeats its first point
  WallCondition condition = WallCondition::no_slip;
  WallVelocity velocity;  // empty: fixed
  // A symmetry plane (held by ghosts as a free-slip wall): the dummies of the other walls and
  // bodies within reach of it are mirrored across it as well (mirror_dummies_across), and a
  // particle that ends a step beyond it becomes its mirror image (SphSolver).
  bool symmetry = false;
};

/// A wall's current geometry: the polyline moved with its prescribed velocity, per segment the
/// unit normal pointing into the soil (side: +1 when that is the left normal, -1 otherwise), and
/// the velocity of every polyline point.
struct WallGeometry {
  std::vector<Vec2> points;
  std::vector<int> side;
  std::vector<Vec2> normals;
  std::vector<Vec2> point_velocity;
  // A closed outline (a rigid body) only: per segment, 1 when soil lay in front of it within
  // reach at the start (its dummy rows then go to full depth); empty for an open wall.
  std::vector<char> faces_soil;
};

/// Recomputes the normals after the points moved (keeping each segment's side).
void update_normals(WallGeometry& wall);

/// Segment normals towards the side holding more soil particles within `reach` of the segment
/// (a segment with none takes its neighbours' side); a closed outline's point out of it.
WallGeometry orient_wall(const WallSpec& wall, std::span<const Vec2> soil, double reach);

/// Signed distance of x from segment s (positive on the soil side) and whether x projects onto
/// the segment (parameter in [0, 1]).
double signed_distance(const WallGeometry& wall, std::size_t segment, const Vec2& x,
                       bool* projects_inside = nullptr);

/// Dummy particles in `layers` rows at (k - 1/2) dp behind every segment, spaced dp along it,
/// rows extended by layers * dp past the polyline's ends and joints so corners are filled;
/// duplicates closer than dp/2 are dropped. A closed outline's: the row points inside the body,
/// and behind a face with soil the rows to full depth where the body is thinner (not past the
/// face's ends).
std::vector<Vec2> dummy_particles(const WallGeometry& wall, double dp, int layers);

/// The mirror images across `plane` (a straight symmetry wall) of the dummies within `reach` in
/// front of it, leaving out any within dp/2 of a dummy already in `dummies`: the dummies the
/// other half of a symmetric body has. A rigid footing cut by a symmetry plane has none beyond it
/// otherwise (its side on the plane faces away from it, and its rows stop there).
std::vector<Vec2> mirror_dummies_across(const WallGeometry& plane, std::span<const Vec2> dummies,
                                        double reach, double dp);

/// True when x lies behind a segment of the wall, within `depth` of it, or, for a closed outline
/// (a rigid body), inside it: a soil particle that has penetrated the wall or body.
bool behind_wall(const WallGeometry& wall, const Vec2& x, double depth);

/// The ghost of a soil particle at x with velocity v across segment `segment` (Peng 2015
/// section 4.2): x_ghost is its mirror image across the segment line, v_ghost keeps the tangential
/// velocity and reverses the normal one (relative to the wall, whose velocity is interpolated
/// between the segment's end points). Returns whether the ghost acts: x lies in front of the
/// segment, within `reach`, and projects onto it.
bool mirror_particle(const WallGeometry& wall, std::size_t segment, const Vec2& x, const Vec2& v,
                     double reach, Vec2& x_ghost, Vec2& v_ghost);

/// The segment before the vertex that starts segment `after` (after - 1; for a closed polyline,
/// whose last point repeats the first, the last segment before vertex 0), or -1 when `after`
/// starts the polyline.
std::ptrdiff_t segment_before(const WallGeometry& wall, std::size_t after);

/// The ghost of a soil particle at x in the wedge beyond a convex vertex, where it projects onto
/// neither segment (the soil wraps round the vertex, as round the chorded wall of a cavity): its
/// mirror image across the line through the vertex normal to x - vertex (the point reflection),
/// the velocity's component along `normal` = (x - vertex) / |x - vertex| reversed relative to
/// the vertex's. Without it such a particle had no ghost and slid through the vertex (the SPH
/// cavity at dp 0.35). Returns whether the ghost acts: x lies in the wedge, within `reach`.
bool mirror_at_vertex(const WallGeometry& wall, std::size_t after, const Vec2& x, const Vec2& v,
                      double reach, Vec2& x_ghost, Vec2& v_ghost, Vec2& normal);

}  // namespace duet::sph
