#pragma once
// Walls and rigid bodies acting on the nodes of the explicit SPFEM (Zhang 2018 slides, explicit
// cycle step 7, with the boundary conditions applied to the nodal velocities). A node is in contact
// with a boundary segment when it lies within half a spacing of it on the soil side (the lattice
// puts the first row of nodes dp/2 off a wall) or has just crossed it. Conditions:
//  - bonded (a no-slip wall): the node moves with the wall; it is fixed to it and never released,
//    so a clamp carries tension (bar, cantilever);
//  - rough (a rough rigid body): stick while approaching, released when it would move away;
//  - smooth (a free-slip wall, a smooth rigid body): the normal relative velocity is removed while
//    approaching, the tangential one is free; released when it would move away;
//  - friction (a frictional rigid body): as smooth, with a Coulomb tangential impulse capped by
//    mu times the normal impulse.
// The force of the soil on a boundary is the sum over its nodes of m (a_free - a_constrained).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/scene.hpp"
#include "common/tensor.hpp"

namespace duet::spfem {

// symmetry: smooth, held both ways (a plane of symmetry); smooth only pushes.
enum class NodeCondition { bonded, rough, smooth, friction, symmetry };

/// A wall or a rigid body as the nodes see it. Translating (`velocity`) or, for a radial wall,
/// every point moving away from `centre` at the radial speed of `radial_velocity` (cavity).
struct NodeBoundary {
  std::string name;
  std::vector<Vec2> polyline;  // m, at t = 0; a closed outline repeats its first point
  bool rigid_body = false;     // closed counter-clockwise outline, soil outside
  NodeCondition condition = NodeCondition::bonded;
  double friction = 0.0;  // Coulomb mu (condition friction)
  Schedule velocity;      // translation, m/s
  bool radial = false;
  Vec2 centre = Vec2::Zero();
  Schedule radial_velocity;  // knots (t, v_r, 0)
};

/// A boundary's geometry at one time: its points, per segment the unit normal into the soil and
/// the velocity of every point.
struct BoundaryGeometry {
  std::vector<Vec2> points;
  std::vector<int> side;  // +1: the soil lies left of the segment, -1: right
  std::vector<Vec2> normals;
  std::vector<Vec2> point_velocity;
};

/// Points and point velocities of `boundary` at time t (normals from the stored sides).
void update_geometry(const NodeBoundary& boundary, double t, BoundaryGeometry& geometry);

/// Geometry at t = 0 with each segment's soil side: outside for a rigid body; for a wall, the side
/// holding more of the nodes within `reach` of the segment. A segment that no node projects onto
/// within `reach` (a chord shorter than the spacing, as the cavity's) takes the side of the nearest
/// segment along the wall that has nodes: a wall keeps its soil on one side.
BoundaryGeometry orient_boundary(const NodeBoundary& boundary, std::span<const Vec2> nodes,
                                 double reach);

/// One node touching one boundary: the contact normal (into the soil), its signed distance
/// (negative: crossed) and the boundary's velocity at the contact point.
struct NodeContact {
  std::int32_t node = -1;
  std::int32_t boundary = -1;
  Vec2 normal = Vec2::Zero();
  double distance = 0.0;
  Vec2 boundary_velocity = Vec2::Zero();
  Vec2 point = Vec2::Zero();  // the contact point on the boundary (foot of the projection)
};

/// Contacts of `x` with the boundary: every segment it projects onto within [-depth, reach] of
/// the line on the soil side; for a rigid body also a convex vertex within `reach` when the node
/// projects onto none of its segments. Appends to `out`.
void find_contacts(const BoundaryGeometry& geometry, bool rigid_body, std::int32_t node,
                   std::int32_t boundary, const Vec2& x, double reach, double depth,
                   std::vector<NodeContact>& out);

/// The first node whose path over an increment, x -> x + u, seen in the frame of a wall that
/// translated by `wall_motion` (zero for a radial wall), crosses the wall at the increment's end
/// (`wall_at_end`; path_crosses_polyline, as the driver's check in common/run_checks.cpp). -1:
/// none.
std::int64_t first_node_crossing(const BoundaryGeometry& wall_at_end, const Vec2& wall_motion,
                                 std::span<const Vec2> x, std::span<const Vec2> u);

/// A wall's convex vertex (the cavity's chords): a node in the wedge beyond it, on the soil side of
/// both segments that meet there, projects onto neither, so find_contacts (vertices for rigid
/// bodies only) misses it and the wall walks through it. This touches the vertex within `reach`,
/// along the line from it to the node; false when there is no such vertex. Meant for a wall where
/// find_contacts found nothing.
bool touch_wall_vertex(const BoundaryGeometry& geometry, std::int32_t node, std::int32_t boundary,
                       const Vec2& x, double reach, NodeContact& out);

/// Every contact of `x` with the boundary as both solvers take them: find_contacts, and for a wall
/// where that found none, its convex vertex (touch_wall_vertex). Appends to `out`.
void find_node_contacts(const BoundaryGeometry& geometry, bool rigid_body, std::int32_t node,
                        std::int32_t boundary, const Vec2& x, double reach, double depth,
                        std::vector<NodeContact>& out);

/// The segment of the boundary that `x` projects onto nearest to it on the soil side, with the
/// signed distance in [-depth, max_distance]; false when there is none. (Wall strips: where an
/// attached node sits against its wall.)
bool project_on_boundary(const BoundaryGeometry& geometry, std::int32_t node, std::int32_t boundary,
                         const Vec2& x, double depth, double max_distance, NodeContact& out);

/// Applies one contact to the node's velocity after the free update, `velocity` (in and out),
/// following the condition; returns the velocity change it made (the impulse per unit mass).
Vec2 constrain_velocity(const NodeContact& contact, NodeCondition condition, double friction,
                        Vec2& velocity);

}  // namespace duet::spfem
