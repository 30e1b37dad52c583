// Tests of the node-boundary geometry (spfem/node_contact.hpp) on the cavity's chorded wall: every
// chord faces the soil, also the chords no node projects onto, and a node in the wedge beyond a
// convex vertex touches that vertex.
#include "spfem/node_contact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace duet::spfem {
namespace {

/// A quarter circle of radius 1 as 16 chords from (1, 0) to (0, 1), expanding at 0.1 m/s from the
/// origin (cavity.toml's wall).
NodeBoundary chorded_cavity_wall() {
  NodeBoundary wall;
  wall.name = "cavity";
  wall.condition = NodeCondition::smooth;
  for (int k = 0; k <= 16; ++k) {
    const double angle = 0.5 * std::numbers::pi * k / 16.0;
    wall.polyline.emplace_back(std::cos(angle), std::sin(angle));
  }
  wall.radial = true;
  wall.radial_velocity = {Knot{0.0, Vec2(0.1, 0.0)}};
  return wall;
}

/// The cell centres of a dp lattice in the quarter annulus 1 < r < 4.
std::vector<Vec2> lattice_outside(double dp) {
  std::vector<Vec2> nodes;
  for (double x = 0.5 * dp; x < 4.0; x += dp) {
    for (double y = 0.5 * dp; y < 4.0; y += dp) {
      const double r = std::hypot(x, y);
      if (r > 1.0 && r < 4.0) nodes.emplace_back(x, y);
    }
  }
  return nodes;
}

TEST(NodeContact, EveryChordOfACavityFacesTheSoilAlsoWhereNoNodeProjectsOntoIt) {
  // At dp 0.5 most 0.098 m chords have no node projecting onto them within 2 dp; left to the
  // default side they faced the cavity, and the expanding wall walked through the first row.
  for (const double dp : {0.5, 0.25, 0.1}) {
    const std::vector<Vec2> nodes = lattice_outside(dp);
    const NodeBoundary wall = chorded_cavity_wall();
    const BoundaryGeometry g = orient_boundary(wall, nodes, 2.0 * dp);
    ASSERT_EQ(g.normals.size(), 16U);
    for (std::size_t s = 0; s < 16; ++s) {
      const Vec2 mid = 0.5 * (g.points[s] + g.points[s + 1]);
      EXPECT_GT(g.normals[s].dot(mid.normalized()), 0.99) << "chord " << s << " at dp " << dp;
    }
  }
}

TEST(NodeContact, ANodeBeyondAConvexVertexOfAWallTouchesIt) {
  const std::vector<Vec2> nodes = lattice_outside(0.5);
  const NodeBoundary wall = chorded_cavity_wall();
  BoundaryGeometry g = orient_boundary(wall, nodes, 1.0);
  update_geometry(wall, 0.5, g);  // the wall at r = 1.05
  const double radius = 1.05;
  const double reach = 0.25;
  // On the bisector of vertex 8 (45 deg), 0.061 m out: in the wedge of the two chords' normals,
  // so it projects onto neither chord.
  const Vec2 x = Vec2(0.75, 0.75);
  std::vector<NodeContact> found;
  find_contacts(g, false, 0, 0, x, reach, 0.5, found);
  EXPECT_TRUE(found.empty());
  NodeContact c;
  ASSERT_TRUE(touch_wall_vertex(g, 0, 0, x, reach, c));
  const Vec2 radial = x.normalized();
  EXPECT_NEAR(c.normal.dot(radial), 1.0, 1e-12);
  EXPECT_NEAR(c.distance, x.norm() - radius, 1e-11);
  EXPECT_NEAR((c.point - radius * radial).norm(), 0.0, 1e-12);
  EXPECT_NEAR((c.boundary_velocity - 0.1 * radial).norm(), 0.0, 1e-12);  // the wall's motion
  // Beyond reach, inside the cavity, or past the wall's ends: no vertex.
  EXPECT_FALSE(touch_wall_vertex(g, 0, 0, 1.3 * radius * radial, reach, c));
  EXPECT_FALSE(touch_wall_vertex(g, 0, 0, 0.98 * radius * radial, reach, c));
  EXPECT_FALSE(touch_wall_vertex(g, 0, 0, Vec2(radius + 0.1, -0.05), reach, c));
}

TEST(NodeContact, APathThroughAMovingWallCrossesItAndANodeFollowingTheWallDoesNot) {
  // A floor y = 0 that rose by 0.1 m over the increment (at y = 0.1 at its end), soil above.
  BoundaryGeometry floor;
  floor.points = {Vec2(0.0, 0.1), Vec2(1.0, 0.1)};
  const Vec2 rise(0.0, 0.1);
  // 0: dp/2 above the floor, carried with it; 1: still, its gap closing from 0.12 to 0.02 m;
  // 2: from 0.3 m down to -0.05 m: through the floor.
  const std::vector<Vec2> x = {Vec2(0.2, 0.05), Vec2(0.5, 0.12), Vec2(0.8, 0.3)};
  std::vector<Vec2> u = {rise, Vec2::Zero(), Vec2(0.0, -0.35)};
  EXPECT_EQ(first_node_crossing(floor, rise, x, u), 2);
  u[2] = Vec2(0.0, -0.15);  // to 0.15: above the floor's end position
  EXPECT_EQ(first_node_crossing(floor, rise, x, u), -1);
  // Past the wall's end: no crossing.
  u[2] = Vec2(0.5, -0.35);
  EXPECT_EQ(first_node_crossing(floor, rise, x, u), -1);
}

}  // namespace
}  // namespace duet::spfem
