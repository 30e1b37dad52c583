// Ghosts of free-slip walls (sph/walls.hpp): across a segment where a particle projects onto it,
// and across a convex vertex for a particle in the wedge beyond it, where it projects onto
// neither segment (the soil round a chorded cavity wall).
#include "sph/walls.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace duet::sph {
namespace {

/// A wall of the given points, the normals on the given side of each segment (left: +1), still.
WallGeometry wall_of(std::vector<Vec2> points, int side) {
  WallGeometry w;
  w.points = std::move(points);
  for (std::size_t s = 0; s + 1 < w.points.size(); ++s) {
    const Vec2 t = (w.points[s + 1] - w.points[s]).normalized();
    w.side.push_back(side);
    w.normals.push_back(side * Vec2(-t.y(), t.x()));
  }
  w.point_velocity.assign(w.points.size(), Vec2::Zero());
  return w;
}

Vec2 polar(double r, double degrees) {
  const double a = degrees * std::numbers::pi / 180.0;
  return r * Vec2(std::cos(a), std::sin(a));
}

TEST(Walls, AParticleBeyondAConvexVertexIsMirroredThroughIt) {
  // A quarter cavity of radius 1 in two chords, the soil outside (normals away from the centre)
  const WallGeometry cavity = wall_of({polar(1, 0), polar(1, 45), polar(1, 90)}, -1);
  ASSERT_GT(cavity.normals[0].dot(polar(1, 22.5)), 0.0);
  const Vec2 vertex = polar(1, 45);
  const Vec2 x = vertex + polar(0.1, 45);  // radially out from the vertex
  const Vec2 v = -polar(2.0, 45);          // moving onto it
  Vec2 xg, vg, n;
  // Neither segment has a ghost for it: it projects onto neither
  EXPECT_FALSE(mirror_particle(cavity, 0, x, v, 0.5, xg, vg));
  EXPECT_FALSE(mirror_particle(cavity, 1, x, v, 0.5, xg, vg));
  // The vertex does: the point reflection, the normal velocity reversed
  ASSERT_TRUE(mirror_at_vertex(cavity, 1, x, v, 0.5, xg, vg, n));
  EXPECT_NEAR((xg - (vertex - polar(0.1, 45))).norm(), 0.0, 1e-15);
  EXPECT_NEAR((n - polar(1, 45)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((vg - polar(2.0, 45)).norm(), 0.0, 1e-14);
  // Tangential motion is kept
  const Vec2 slide = polar(1.0, 135);
  ASSERT_TRUE(mirror_at_vertex(cavity, 1, x, slide, 0.5, xg, vg, n));
  EXPECT_NEAR((vg - slide).norm(), 0.0, 1e-14);
  // Out of reach, or where it projects onto a segment: no vertex ghost
  EXPECT_FALSE(mirror_at_vertex(cavity, 1, vertex + polar(0.6, 45), v, 0.5, xg, vg, n));
  const Vec2 beside = polar(1.1, 30);
  EXPECT_FALSE(mirror_at_vertex(cavity, 1, beside, v, 0.5, xg, vg, n));
  EXPECT_TRUE(mirror_particle(cavity, 0, beside, v, 0.5, xg, vg));
  // The start of an open polyline is no vertex
  EXPECT_EQ(segment_before(cavity, 0), -1);
  EXPECT_FALSE(mirror_at_vertex(cavity, 0, polar(1.1, -10), v, 0.5, xg, vg, n));
}

TEST(Walls, EveryPointNearAVertexHasOneGhostConvexAndNoneFromAConcaveVertex) {
  // Convex: every point in front of the chorded cavity, within reach of its middle vertex,
  // gets exactly one acting ghost (from a segment or from the vertex)
  const WallGeometry cavity = wall_of({polar(1, 0), polar(1, 45), polar(1, 90)}, -1);
  // Concave: the inside corner of a box, soil inside (left normals)
  const WallGeometry box = wall_of({Vec2(0, 0), Vec2(1, 0), Vec2(1, 1)}, 1);
  Vec2 xg, vg, n;
  int convex_points = 0;
  for (int i = 0; i <= 40; ++i) {
    for (int j = 0; j <= 40; ++j) {
      const Vec2 x = polar(1, 45) + Vec2(-0.4 + 0.02 * i, -0.4 + 0.02 * j);
      const bool in_front =
          signed_distance(cavity, 0, x) > 0.0 && signed_distance(cavity, 1, x) > 0.0;
      if (in_front && (x - polar(1, 45)).norm() < 0.3) {
        ++convex_points;
        const int ghosts = int(mirror_particle(cavity, 0, x, Vec2::Zero(), 0.5, xg, vg)) +
                           int(mirror_particle(cavity, 1, x, Vec2::Zero(), 0.5, xg, vg)) +
                           int(mirror_at_vertex(cavity, 1, x, Vec2::Zero(), 0.5, xg, vg, n));
        EXPECT_EQ(ghosts, 1) << x.transpose();
      }
      const Vec2 y = Vec2(1, 0) + Vec2(-0.4 + 0.02 * i, -0.4 + 0.02 * j);
      EXPECT_FALSE(mirror_at_vertex(box, 1, y, Vec2::Zero(), 0.5, xg, vg, n)) << y.transpose();
    }
  }
  EXPECT_GT(convex_points, 100);
}

TEST(Walls, EveryChordOfACavityFacesTheSoilThoughNoParticleProjectsOntoSome) {
  // The cavity's quarter wall in 16 chords of 0.098 m, the soil on two rings of a coarse lattice
  // outside it (4 and 6 particles): most chords have no particle projecting onto them. Each must
  // still face the soil (away from the centre); with the left normal they faced the cavity, and
  // SPH's cavity at dp 0.5 held no ghost there (benchmarks/RESULTS.md).
  WallSpec spec{"cavity", {}, WallCondition::free_slip, {}};
  for (int k = 0; k <= 16; ++k) spec.polyline.push_back(polar(1.0, 90.0 * k / 16.0));
  std::vector<Vec2> soil;
  for (int i = 0; i < 4; ++i) soil.push_back(polar(1.25, 90.0 * (i + 0.5) / 4.0));
  for (int i = 0; i < 6; ++i) soil.push_back(polar(1.75, 90.0 * (i + 0.5) / 6.0));
  const double reach = 1.0;
  const WallGeometry wall = orient_wall(spec, soil, reach);
  int without_soil = 0;
  for (std::size_t s = 0; s + 1 < wall.points.size(); ++s) {
    bool any = false;
    for (const Vec2& x : soil) {
      bool inside = false;
      const double d = signed_distance(wall, s, x, &inside);
      any = any || (inside && std::abs(d) <= reach);
    }
    without_soil += any ? 0 : 1;
    const Vec2 middle = 0.5 * (wall.points[s] + wall.points[s + 1]);
    EXPECT_GT(wall.normals[s].dot(middle), 0.0) << "chord " << s;
  }
  EXPECT_GE(without_soil, 8);  // the case the rule is for
}

/// The footing of footing.toml (1 m x 0.3 m, base at y = 5) on soil sampled on the lattice of
/// spacing dp below it, as the solver lays out its walls.
struct FootingOnSoil {
  WallGeometry footing;
  std::vector<Vec2> dummies;
};

FootingOnSoil footing_on_soil(double dp, double reach) {
  std::vector<Vec2> soil;
  for (double x = 0.5 * dp; x < 3.0; x += dp) {
    for (double y = 5.0 - 0.5 * dp; y > 3.0; y -= dp) soil.emplace_back(x, y);
  }
  // counter-clockwise, as footing.toml lists it
  const WallSpec spec{
      "footing", {{0, 5}, {1, 5}, {1, 5.3}, {0, 5.3}, {0, 5}}, WallCondition::no_slip, {}};
  FootingOnSoil out;
  out.footing = orient_wall(spec, soil, reach);
  out.dummies = dummy_particles(out.footing, dp, 3);
  return out;
}

TEST(Walls, EveryFaceOfARigidBodyFacesOutOfIt) {
  // Arrange: the footing is thinner than the reach (0.3 m < 0.7 m at dp 0.25): counted, the soil
  // below it lies within reach of its top, and no particle projects onto its sides
  for (const double dp : {0.25, 0.1}) {
    // Act
    const WallGeometry footing = footing_on_soil(dp, 2.83 * dp).footing;
    // Assert: base down, right side right, top up, left side left
    EXPECT_EQ(footing.normals[0], Vec2(0.0, -1.0)) << dp;
    EXPECT_EQ(footing.normals[1], Vec2(1.0, 0.0)) << dp;
    EXPECT_EQ(footing.normals[2], Vec2(0.0, 1.0)) << dp;
    EXPECT_EQ(footing.normals[3], Vec2(-1.0, 0.0)) << dp;
    // only the base has soil in front of it
    EXPECT_EQ(footing.faces_soil, (std::vector<char>{1, 0, 0, 0})) << dp;
  }
}

TEST(Walls, ARigidBodysDummiesFillItAndTheKernelBehindItsBaseButNeverBesideIt) {
  for (const double dp : {0.25, 1.0 / 6.0, 0.1}) {
    // Arrange, act
    const std::vector<Vec2> dummies = footing_on_soil(dp, 2.83 * dp).dummies;
    // Assert: none beside the footing (0 < x < 1, the symmetry plane's images are the solver's),
    // none below its base; the columns are the soil's (x = (i + 1/2) dp), and behind the base
    // three rows at (k - 1/2) dp, the body thinner than that or not
    std::vector<int> per_column(static_cast<std::size_t>(std::lround(1.0 / dp)), 0);
    for (const Vec2& x : dummies) {
      EXPECT_GT(x.x(), 0.0) << dp;
      EXPECT_LT(x.x(), 1.0) << dp;
      EXPECT_GT(x.y(), 5.0) << dp;
      const double column = x.x() / dp - 0.5;
      EXPECT_NEAR(column, std::round(column), 1e-9) << dp;
      const double row = (x.y() - 5.0) / dp + 0.5;
      EXPECT_NEAR(row, std::round(row), 1e-9) << dp;
      EXPECT_LE(std::lround(row), 3) << dp;
      per_column.at(static_cast<std::size_t>(std::lround(column))) += 1;
    }
    for (const int count : per_column) EXPECT_EQ(count, 3) << dp;
  }
}

TEST(Walls, NoDummyOfAConeLiesInTheSoilInFrontOfItsFaces) {
  // Arrange: a cone (a penetrometer's tip, 60 degrees) over soil sampled at dp 0.05 below its
  // tip's level and round it, clockwise; and a square turned 45 degrees (a diamond), its lower
  // faces over the same soil
  const double dp = 0.05;
  std::vector<Vec2> soil;
  for (double x = -1.0 + 0.5 * dp; x < 1.0; x += dp) {
    for (double y = -0.5 * dp; y > -1.0; y -= dp) soil.emplace_back(x, y);
  }
  const double half = std::tan(std::numbers::pi / 6.0) * 0.4;  // 0.4 m high, 60 degree apex
  const std::vector<std::vector<Vec2>> bodies = {
      {{0.0, 0.0}, {-half, 0.4}, {half, 0.4}, {0.0, 0.0}},
      {{0.0, 0.0}, {0.2, 0.2}, {0.0, 0.4}, {-0.2, 0.2}, {0.0, 0.0}}};
  for (const std::vector<Vec2>& outline : bodies) {
    const WallSpec spec{"body", outline, WallCondition::no_slip, {}};
    // Act
    const WallGeometry body = orient_wall(spec, soil, 2.83 * dp);
    const std::vector<Vec2> dummies = dummy_particles(body, dp, 3);
    // Assert: some dummies, and none in front of a face that has soil before it (in the soil)
    ASSERT_GT(dummies.size(), 10u);
    for (const Vec2& x : dummies) {
      for (std::size_t s = 0; s + 1 < body.points.size(); ++s) {
        if (body.faces_soil[s] == 0) continue;
        bool inside = false;
        const double d = signed_distance(body, s, x, &inside);
        EXPECT_FALSE(inside && d > 1e-12) << "dummy (" << x.x() << ", " << x.y() << ") in front "
                                          << "of face " << s << " by " << d;
      }
      EXPECT_GT(x.y(), 0.0) << x.x();  // above the tip: never below the soil's top
    }
  }
}

TEST(Walls, ASoilParticleIsInsideABodyOnlyWithinItsOutline) {
  // Arrange: the footing at dp 0.25 (dummy depth 0.75 m, more than its 0.3 m)
  const WallGeometry footing = footing_on_soil(0.25, 0.7).footing;
  // Act, assert: under the base, within the depth of its top's rows, is not inside the body
  EXPECT_FALSE(behind_wall(footing, Vec2(0.5, 4.875), 0.75));
  EXPECT_FALSE(behind_wall(footing, Vec2(1.1, 5.1), 0.75));
  EXPECT_TRUE(behind_wall(footing, Vec2(0.5, 5.01), 0.75));
  EXPECT_TRUE(behind_wall(footing, Vec2(0.99, 5.29), 0.75));
}

TEST(Walls, DummiesWithinReachOfASymmetryPlaneHaveTheirImagesBeyondIt) {
  // Arrange: the plane x = 0, the soil on its right; dummies at 0.05 and 0.15 m from it, one
  // beyond the reach, and one whose image is already a dummy
  const WallGeometry plane = wall_of({{0.0, 0.0}, {0.0, 10.0}}, -1);
  ASSERT_EQ(plane.normals[0], Vec2(1.0, 0.0));
  const std::vector<Vec2> dummies = {
      {0.05, 5.05}, {0.15, 5.05}, {0.95, 5.05}, {0.05, 6.0}, {-0.05, 6.0}};
  // Act
  const std::vector<Vec2> images = mirror_dummies_across(plane, dummies, 0.28, 0.1);
  // Assert
  const std::vector<Vec2> expected = {{-0.05, 5.05}, {-0.15, 5.05}};
  EXPECT_EQ(images, expected);
}

}  // namespace
}  // namespace duet::sph
