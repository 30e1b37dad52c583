// Plane geometry of scenes: areas, orientation, point in polygon, distances, overlap, schedules.
#include "common/geometry.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace duet {
namespace {

std::vector<Vec2> square(double x0, double y0, double side) {
  return {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
}

// An L: the square [0, 2] x [0, 2] without its top-right quarter (area 3).
std::vector<Vec2> l_shape() {
  return {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
}

TEST(Geometry, SignedAreaIsPositiveCounterClockwiseAndExactForAnLShape) {
  const std::vector<Vec2> l = l_shape();
  EXPECT_DOUBLE_EQ(signed_area(l), 3.0);
  const std::vector<Vec2> clockwise(l.rbegin(), l.rend());
  EXPECT_DOUBLE_EQ(signed_area(clockwise), -3.0);
}

TEST(Geometry, MakeCounterClockwiseReversesAClockwisePolygonOnly) {
  std::vector<Vec2> clockwise = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  make_counter_clockwise(clockwise);
  EXPECT_GT(signed_area(clockwise), 0.0);
  std::vector<Vec2> already = square(0, 0, 1);
  make_counter_clockwise(already);
  EXPECT_EQ(already, square(0, 0, 1));
}

TEST(Geometry, PointInPolygonSeesTheNotchOfANonConvexPolygon) {
  EXPECT_TRUE(point_in_polygon({0.5, 1.5}, l_shape()));
  EXPECT_TRUE(point_in_polygon({1.5, 0.5}, l_shape()));
  EXPECT_FALSE(point_in_polygon({1.5, 1.5}, l_shape()));  // the missing quarter
  EXPECT_FALSE(point_in_polygon({-0.1, 0.5}, l_shape()));
}

TEST(Geometry, PointOnASharedEdgeBelongsToExactlyOneOfTwoTilingSquares) {
  const auto left = square(0, 0, 1);
  const auto right = square(1, 0, 1);
  const auto above = square(0, 1, 1);
  const Vec2 on_vertical_edge(1.0, 0.5);
  const Vec2 on_horizontal_edge(0.5, 1.0);
  EXPECT_NE(point_in_polygon(on_vertical_edge, left), point_in_polygon(on_vertical_edge, right));
  EXPECT_NE(point_in_polygon(on_horizontal_edge, left),
            point_in_polygon(on_horizontal_edge, above));
}

TEST(Geometry, SegmentDistanceIsPerpendicularInsideAndToTheEndOutside) {
  EXPECT_DOUBLE_EQ(segment_distance({0.5, 2.0}, {0, 0}, {1, 0}), 2.0);
  EXPECT_DOUBLE_EQ(segment_distance({4.0, 4.0}, {0, 0}, {1, 0}), 5.0);  // 3-4-5 from (1, 0)
  EXPECT_DOUBLE_EQ(polyline_distance({2.0, 0.5}, std::vector<Vec2>{{0, 0}, {1, 0}, {1, 1}}), 1.0);
}

TEST(Geometry, PolygonsSharingAnEdgeOrAVertexDoNotOverlap) {
  EXPECT_FALSE(polygons_overlap(square(0, 0, 1), square(1, 0, 1)));
  EXPECT_FALSE(polygons_overlap(square(0, 0, 1), square(1, 1, 1)));
  EXPECT_FALSE(polygons_overlap(square(0, 0, 1), square(3, 0, 1)));
}

TEST(Geometry, CrossingContainedAndCoincidentPolygonsOverlap) {
  const std::vector<Vec2> wide = {{-1, 0.4}, {2, 0.4}, {2, 0.6}, {-1, 0.6}};
  EXPECT_TRUE(polygons_overlap(square(0, 0, 1), wide));             // edges cross
  EXPECT_TRUE(polygons_overlap(square(0, 0, 3), square(1, 1, 1)));  // contained
  EXPECT_TRUE(polygons_overlap(square(0, 0, 1), square(0, 0, 1)));  // coincident
  EXPECT_TRUE(polygons_overlap(l_shape(), square(0.5, 0.5, 1)));    // into a non-convex one
  EXPECT_FALSE(polygons_overlap(l_shape(), square(1, 1, 1)));       // fills the notch
}

TEST(Geometry, APathThroughAVertexOfAPolylineCrossesItAndOneTouchingItDoesNot) {
  // Two chords of a cavity meeting at (1, 1) on the diagonal, soil outside (x + y > 2).
  const std::vector<Vec2> wall = {Vec2(1.2, 0.7), Vec2(1.0, 1.0), Vec2(0.7, 1.2)};
  // Along the diagonal, through the vertex: segments_cross counts it for neither chord.
  const Vec2 from(1.1, 1.1), to(0.95, 0.95);
  EXPECT_FALSE(segments_cross(from, to, wall[0], wall[1]));
  EXPECT_FALSE(segments_cross(from, to, wall[1], wall[2]));
  EXPECT_TRUE(path_crosses_polyline(from, to, wall));
  EXPECT_TRUE(path_crosses_polyline(to, from, wall));  // either way
  // Ending on the vertex, or grazing it and staying outside: no crossing.
  EXPECT_FALSE(path_crosses_polyline(from, Vec2(1.0, 1.0), wall));
  EXPECT_FALSE(path_crosses_polyline(Vec2(1.3, 0.9), Vec2(0.9, 1.3), wall));
  // Through a chord's interior, as before.
  EXPECT_TRUE(path_crosses_polyline(Vec2(1.2, 0.95), Vec2(1.0, 0.85), wall));
  EXPECT_FALSE(path_crosses_polyline(Vec2(1.3, 1.3), Vec2(1.2, 1.2), wall));
}

TEST(Geometry, BowTieIsNotASimplePolygon) {
  EXPECT_FALSE(is_simple_polygon(std::vector<Vec2>{{0, 0}, {1, 1}, {1, 0}, {0, 1}}));
  EXPECT_TRUE(is_simple_polygon(l_shape()));
}

TEST(Geometry, ScheduleInterpolatesLinearlyAndHoldsBeyondItsKnots) {
  const Schedule s = {{1.0, {0.0, 0.0}}, {3.0, {2.0, -4.0}}};
  EXPECT_EQ(schedule_value(s, 0.0), Vec2(0.0, 0.0));
  EXPECT_EQ(schedule_value(s, 2.0), Vec2(1.0, -2.0));
  EXPECT_EQ(schedule_value(s, 10.0), Vec2(2.0, -4.0));
  EXPECT_EQ(schedule_value({}, 1.0), Vec2::Zero());
}

TEST(Geometry, ScheduleIntegralOfTheOedometerPlateReturnsToTheStart) {
  // Down at 1 cm/s for 5 s, then up at 1 cm/s (a jump at t = 5 s).
  const Schedule plate = {
      {0.0, {0.0, -0.01}}, {5.0, {0.0, -0.01}}, {5.0, {0.0, 0.01}}, {10.0, {0.0, 0.01}}};
  EXPECT_NEAR(schedule_integral(plate, 5.0).y(), -0.05, 1e-15);
  EXPECT_NEAR(schedule_integral(plate, 7.5).y(), -0.025, 1e-15);
  EXPECT_NEAR(schedule_integral(plate, 10.0).y(), 0.0, 1e-15);
  // A ramp 0 -> 2 over [1, 3], held after: 1/2 * 2 * 2 + 2 * 1 = 4 at t = 4.
  const Schedule ramp = {{1.0, {0.0, 0.0}}, {3.0, {2.0, 0.0}}};
  EXPECT_NEAR(schedule_integral(ramp, 4.0).x(), 4.0, 1e-14);
}

TEST(Geometry, RadialWallGrowsItsRadiusByTheIntegratedSpeed) {
  Wall cavity;
  for (int i = 0; i <= 8; ++i) {
    const double angle = std::numbers::pi / 2 * i / 8;
    cavity.points.emplace_back(std::cos(angle), std::sin(angle));
  }
  cavity.radial = true;
  cavity.radial_velocity = {{0.0, {0.1, 0.0}}};
  for (const Vec2& p : wall_points_at(cavity, 10.0)) EXPECT_NEAR(p.norm(), 2.0, 1e-14);
}

TEST(Geometry, TranslatingWallMovesEveryPointByTheSameDisplacement) {
  Wall plate;
  plate.points = {{0.0, 1.0}, {0.5, 1.0}};
  plate.velocity = {{0.0, {0.0, -0.01}}};
  const auto moved = wall_points_at(plate, 2.0);
  EXPECT_NEAR(moved[0].y(), 0.98, 1e-15);
  EXPECT_NEAR(moved[1].y(), 0.98, 1e-15);
  EXPECT_NEAR(polyline_length(moved), 0.5, 1e-15);
}

TEST(Geometry, SegmentsWithoutMaterialTakeTheSideOfTheNearestThatHasSome) {
  // 0: no material projects onto the segment. Each takes the nearest counted side along the
  // wall, the earlier on a tie; with none counted, +1.
  std::vector<int> side = {0, -1, 0, 0, 1, 0};
  fill_sides_from_neighbours(side);
  EXPECT_EQ(side, (std::vector<int>{-1, -1, -1, 1, 1, 1}));
  std::vector<int> tie = {1, 0, -1};
  fill_sides_from_neighbours(tie);
  EXPECT_EQ(tie, (std::vector<int>{1, 1, -1}));
  std::vector<int> none = {0, 0};
  fill_sides_from_neighbours(none);
  EXPECT_EQ(none, (std::vector<int>{1, 1}));
}

}  // namespace
}  // namespace duet
