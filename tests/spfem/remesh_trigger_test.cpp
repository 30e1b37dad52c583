// Tests of the remesh-on-angle trigger (spfem/remesh_trigger.hpp): the plain threshold on the
// smallest angle, the limit relative to a triangle's angle at its remesh, inversion, and the
// smallest angle it reports against smallest_angle().
#include "spfem/remesh_trigger.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace duet::spfem {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// An isosceles triangle with apex angle theta_deg at the origin (its smallest angle for
/// theta < 60 deg), counter-clockwise: (0, 0), (1, 0), (cos theta, sin theta).
std::vector<Vec2> apex(double theta_deg) {
  return {Vec2(0.0, 0.0), Vec2(1.0, 0.0),
          Vec2(std::cos(theta_deg * kDegree), std::sin(theta_deg * kDegree))};
}

AlphaMesh one_triangle() {
  AlphaMesh mesh;
  mesh.triangles = {{0, 1, 2}};
  return mesh;
}

TEST(RemeshTrigger, PlainThresholdFiresBelowTheRemeshAngle) {
  // Arrange: born at 40 deg, limit 15 deg for every triangle (fraction 0)
  const AlphaMesh mesh = one_triangle();
  RemeshTrigger trigger;
  const double born = arm_remesh_trigger(mesh, apex(40.0), 15.0, 0.0, trigger);
  double above = 0.0, below = 0.0;
  // Act
  const bool due_above = remesh_due(mesh, apex(15.5), trigger, above);
  const bool due_below = remesh_due(mesh, apex(14.5), trigger, below);
  // Assert
  EXPECT_NEAR(born, 40.0, 1e-10);
  EXPECT_FALSE(due_above);
  EXPECT_TRUE(due_below);
  EXPECT_NEAR(above, 15.5, 1e-10);
  EXPECT_NEAR(below, 14.5, 1e-10);
}

TEST(RemeshTrigger, PlainThresholdFiresAtOnceOnATriangleBornBelowIt) {
  // Arrange: born at 10 deg, below remesh_angle 15 deg
  const AlphaMesh mesh = one_triangle();
  RemeshTrigger trigger;
  arm_remesh_trigger(mesh, apex(10.0), 15.0, 0.0, trigger);
  double angle = 0.0;
  // Act, Assert: the plain rule asks for a new mesh although nothing has moved
  EXPECT_TRUE(remesh_due(mesh, apex(10.0), trigger, angle));
}

TEST(RemeshTrigger, FractionLimitsATriangleBornBelowTheThresholdToItsOwnAngle) {
  // Arrange: born at 20 deg with fraction 0.5: limit min(15, 10) = 10 deg
  const AlphaMesh mesh = one_triangle();
  RemeshTrigger trigger;
  arm_remesh_trigger(mesh, apex(20.0), 15.0, 0.5, trigger);
  double angle = 0.0;
  // Act, Assert: 12 deg is below remesh_angle but above half its birth angle
  EXPECT_FALSE(remesh_due(mesh, apex(12.0), trigger, angle));
  EXPECT_TRUE(remesh_due(mesh, apex(9.9), trigger, angle));
}

TEST(RemeshTrigger, FractionKeepsTheRemeshAngleForAWellShapedTriangle) {
  // Arrange: born at 45 deg with fraction 0.5: limit min(15, 22.5) = 15 deg
  const AlphaMesh mesh = one_triangle();
  RemeshTrigger trigger;
  arm_remesh_trigger(mesh, apex(45.0), 15.0, 0.5, trigger);
  double angle = 0.0;
  // Act, Assert
  EXPECT_FALSE(remesh_due(mesh, apex(15.1), trigger, angle));
  EXPECT_TRUE(remesh_due(mesh, apex(14.9), trigger, angle));
}

TEST(RemeshTrigger, InversionFiresEvenWithoutAnAngleLimit) {
  // Arrange: remesh_angle 0 (no limit); the apex pushed below the base turns the triangle over
  const AlphaMesh mesh = one_triangle();
  RemeshTrigger trigger;
  arm_remesh_trigger(mesh, apex(30.0), 0.0, 0.0, trigger);
  double angle = 0.0;
  // Act
  const bool kept = remesh_due(mesh, apex(5.0), trigger, angle);
  const bool inverted = remesh_due(mesh, apex(-5.0), trigger, angle);
  // Assert: clockwise, the signed angles are -5 deg at the apex and -(180 - 5) / 2 = -87.5 deg at
  // the base corners; the smallest is the latter
  EXPECT_FALSE(kept);
  EXPECT_TRUE(inverted);
  EXPECT_NEAR(angle, -87.5, 1e-10);
}

TEST(RemeshTrigger, ReportsTheSmallestAngleOfAPerturbedLatticeMesh) {
  // Arrange: a 10 x 6 square lattice split into triangles, every node moved at random
  std::vector<Vec2> x;
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 10; ++i) x.push_back(Vec2(i, j));
  }
  AlphaMesh mesh;
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 9; ++i) {
      const int a = j * 10 + i;
      mesh.triangles.push_back({a, a + 1, a + 11});
      mesh.triangles.push_back({a, a + 11, a + 10});
    }
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (Vec2& p : x) p += Vec2(u(rng), u(rng));
  RemeshTrigger trigger;
  // Act
  const double armed = arm_remesh_trigger(mesh, x, 15.0, 0.5, trigger);
  double measured = 0.0;
  remesh_due(mesh, x, trigger, measured);
  // Assert: the same smallest angle as the mesh's own measure; nothing has moved since the arm
  EXPECT_NEAR(armed, smallest_angle(mesh, x), 1e-10);
  EXPECT_NEAR(measured, smallest_angle(mesh, x), 1e-10);
  EXPECT_FALSE(remesh_due(mesh, x, trigger, measured));
}

}  // namespace
}  // namespace duet::spfem
