#include "common/frame_geometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace duet {
namespace {

TEST(SurfaceEdges, TwoTrianglesShareOneEdge) {
  // The unit square cut along its diagonal 0-2: the four sides are the surface, the diagonal not.
  const std::vector<MeshTriangle> triangles = {{0, 1, 2}, {0, 2, 3}};
  const std::vector<MeshEdge> edges = surface_edges(triangles);
  ASSERT_EQ(edges.size(), 4u);
  for (const MeshEdge& e : edges) {
    EXPECT_FALSE((e[0] == 0 && e[1] == 2) || (e[0] == 2 && e[1] == 0));
  }
  // Oriented as in their triangle: counter-clockwise around the square.
  EXPECT_NE(std::find(edges.begin(), edges.end(), MeshEdge{0, 1}), edges.end());
  EXPECT_NE(std::find(edges.begin(), edges.end(), MeshEdge{3, 0}), edges.end());
}

TEST(SurfaceEdges, AFanAroundANodeHasOnlyItsRim) {
  // Six triangles around node 0: the rim (6 edges) is the surface, the spokes are not.
  std::vector<MeshTriangle> triangles;
  for (std::int32_t k = 0; k < 6; ++k) triangles.push_back({0, 1 + k, 1 + (k + 1) % 6});
  const std::vector<MeshEdge> edges = surface_edges(triangles);
  ASSERT_EQ(edges.size(), 6u);
  for (const MeshEdge& e : edges) EXPECT_TRUE(e[0] != 0 && e[1] != 0);
}

TEST(BoundaryLines, WallsOpenRigidBodiesClosedAndMoved) {
  Scene scene;
  Wall wall;
  wall.name = "base";
  wall.points = {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}};
  wall.velocity = {{0.0, {0.5, 0.0}}};  // 0.5 m/s to the right
  scene.walls.push_back(wall);
  RigidBody footing;
  footing.name = "footing";
  footing.outline = {{0.0, 1.0}, {0.2, 1.0}, {0.2, 1.1}, {0.0, 1.1}};
  footing.velocity = {{0.0, {0.0, -0.1}}, {1.0, {0.0, -0.3}}};  // accelerating down
  scene.rigid_bodies.push_back(footing);

  const BoundaryLines at0 = boundary_lines_at(scene, 0.0);
  EXPECT_EQ(at0.points.size(), 7u);
  ASSERT_EQ(at0.segments.size(), 2u + 4u);  // open polyline of 3 points, closed square
  EXPECT_EQ(at0.owner, (std::vector<std::int32_t>{0, 0, 1, 1, 1, 1}));
  EXPECT_EQ(at0.segments.back(), (MeshEdge{6, 3}));

  const BoundaryLines at1 = boundary_lines_at(scene, 1.0);
  EXPECT_DOUBLE_EQ(at1.points[0].x(), 0.5);
  // integral of -0.1 -> -0.3 over 1 s: -0.2 m
  EXPECT_NEAR(at1.points[3].y(), 0.8, 1e-15);
  // Before the clock starts (gravity loading), as at 0.
  EXPECT_EQ(boundary_lines_at(scene, -0.5).points[3], at0.points[3]);
}

}  // namespace
}  // namespace duet
