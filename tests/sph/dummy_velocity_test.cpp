// The extrapolated velocity of a no-slip dummy particle (sph/dummy_velocity.hpp, Morris 1997 /
// Bui 2008): v_B = v_w - (d_B / d_A)(v_A - v_w) below the cap beta = 1 + d_B / d_A <= 1.5, the
// cap above it, and the wall line seen from a soil particle (the scene key that selects it:
// tests/common/scene_loader_test.cpp).
#include "sph/dummy_velocity.hpp"

#include <gtest/gtest.h>

namespace duet::sph {
namespace {

constexpr double kDp = 0.002;  // m

/// A floor along y = 0 from x = 0 to 0.6 m and a back wall x = 0 up to 0.15 m, soil in x, y > 0
/// (the collapse scenes' walls as one polyline), normals into the soil.
WallGeometry floor_and_back_wall() {
  WallSpec spec;
  spec.polyline = {Vec2(0.0, 0.15), Vec2(0.0, 0.0), Vec2(0.6, 0.0)};
  const std::vector<Vec2> soil{Vec2(0.001, 0.05), Vec2(0.1, 0.001)};
  return orient_wall(spec, soil, 0.01);
}

TEST(DummyVelocity, BelowTheCapIsTheLinearExtrapolationThroughTheWall) {
  // Arrange: a particle 3 dp in front of a moving wall, a dummy 0.5 dp behind it
  const Vec2 v_a(0.5, 0.3), v_w(0.1, -0.02);
  const double d_a = 3.0 * kDp, d_b = 0.5 * kDp;
  // Act
  const Vec2 v_b = extrapolated_dummy_velocity(v_a, v_w, d_a, d_b);
  // Assert: v_B = v_w - (d_B / d_A)(v_A - v_w) = v_w - (v_A - v_w) / 6
  const Vec2 expected = v_w - (d_b / d_a) * (v_a - v_w);
  EXPECT_NEAR(v_b.x(), expected.x(), 1e-15);
  EXPECT_NEAR(v_b.y(), expected.y(), 1e-15);
  EXPECT_NEAR(v_b.x(), 0.1 - 0.4 / 6.0, 1e-15);
}

TEST(DummyVelocity, AboveTheCapTheDifferenceIsOnePointFiveTimesThatToTheWall) {
  // Arrange: d_B / d_A = 2.5 > beta_max - 1 = 0.5
  const Vec2 v_a(0.5, 0.3), v_w(0.1, -0.02);
  const double d_a = 0.5 * kDp, d_b = 1.25 * kDp;
  // Act
  const Vec2 v_b = extrapolated_dummy_velocity(v_a, v_w, d_a, d_b);
  // Assert: v_A - v_B = 1.5 (v_A - v_w), i.e. v_B = v_w - 0.5 (v_A - v_w)
  EXPECT_NEAR(v_b.x(), 0.1 - 0.5 * 0.4, 1e-15);
  EXPECT_NEAR(v_b.y(), -0.02 - 0.5 * 0.32, 1e-15);
}

TEST(DummyVelocity, TheCapStartsWhereTheRatioReachesOneHalf) {
  // Arrange: just below and just above d_B / d_A = 0.5, v_w = 0
  const Vec2 v_a(1.0, 0.0), v_w = Vec2::Zero();
  // Act
  const Vec2 below = extrapolated_dummy_velocity(v_a, v_w, 2.0 * kDp, 0.999 * kDp);
  const Vec2 above = extrapolated_dummy_velocity(v_a, v_w, 2.0 * kDp, 1.001 * kDp);
  // Assert
  EXPECT_NEAR(below.x(), -0.4995, 1e-14);
  EXPECT_NEAR(above.x(), -0.5, 1e-14);
}

TEST(DummyVelocity, AParticleOnOrBehindTheWallGetsTheCap) {
  const Vec2 v_a(0.2, 0.0), v_w = Vec2::Zero();
  EXPECT_NEAR(extrapolated_dummy_velocity(v_a, v_w, 0.0, 0.5 * kDp).x(), -0.1, 1e-15);
  EXPECT_NEAR(extrapolated_dummy_velocity(v_a, v_w, -0.1 * kDp, 0.5 * kDp).x(), -0.1, 1e-15);
}

TEST(DummyVelocity, ADummyInFrontOfTheWallLineTakesTheWallVelocity) {
  const Vec2 v_b = extrapolated_dummy_velocity(Vec2(0.2, 0.1), Vec2(0.05, 0.0), kDp, -0.5 * kDp);
  EXPECT_NEAR(v_b.x(), 0.05, 1e-15);
  EXPECT_NEAR(v_b.y(), 0.0, 1e-15);
}

TEST(DummyVelocity, ContinuesALinearShearProfileAcrossTheFloor) {
  // Arrange: v(y) = v_w + gamma y over a floor y = 0; soil particle at y = 2.5 dp, dummies in the
  // three rows at y = -(k - 1/2) dp (d_B / d_A = 0.2, 0.6, 1.0: the first below the cap)
  const WallGeometry wall = floor_and_back_wall();
  const Vec2 v_w(0.01, 0.0);
  const double gamma = 3.0;  // 1/s
  const Vec2 x_a(0.1, 2.5 * kDp);
  const Vec2 v_a = v_w + Vec2(gamma * x_a.y(), 0.0);
  // Act
  const WallLine line = nearest_wall_line(wall, 0, x_a);
  const Vec2 x_b(0.1 + kDp, -0.5 * kDp);
  const Vec2 v_b = extrapolated_dummy_velocity(v_a, v_w, line.distance, distance_behind(line, x_b));
  // Assert: the floor is the nearest segment; the dummy lies on the profile, v(y_B)
  EXPECT_NEAR(line.distance, 2.5 * kDp, 1e-15);
  EXPECT_NEAR(distance_behind(line, x_b), 0.5 * kDp, 1e-15);
  EXPECT_NEAR(v_b.x(), v_w.x() + gamma * x_b.y(), 1e-15);
  EXPECT_NEAR(v_b.y(), 0.0, 1e-15);
}

TEST(DummyVelocity, TheNearestSegmentDecidesTheWallLine) {
  // Arrange: a particle 1 dp from the back wall and 10 dp above the floor
  const WallGeometry wall = floor_and_back_wall();
  // Act
  const WallLine line = nearest_wall_line(wall, 3, Vec2(kDp, 10.0 * kDp));
  // Assert: the back wall's line, normal +x, distance 1 dp; a dummy 1.5 dp behind it
  EXPECT_EQ(line.wall, 3);
  EXPECT_NEAR(line.normal.x(), 1.0, 1e-15);
  EXPECT_NEAR(line.distance, kDp, 1e-15);
  EXPECT_NEAR(distance_behind(line, Vec2(-1.5 * kDp, 9.0 * kDp)), 1.5 * kDp, 1e-15);
}

}  // namespace
}  // namespace duet::sph
