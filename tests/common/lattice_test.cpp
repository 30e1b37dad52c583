// Lattice sampling: particle count, total mass and volume of a rectangle and a polygon are exact
// when their edges lie on lattice lines; edge points are shared out without double counting.
#include "common/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "common/geometry.hpp"

namespace duet {
namespace {

Scene scene_with(double spacing, double density, std::vector<std::vector<Vec2>> outlines) {
  Scene scene;
  scene.spacing = spacing;
  Material sand;
  sand.name = "sand";
  sand.model = "linear-elastic";
  sand.density = density;
  scene.materials.push_back(sand);
  for (std::size_t i = 0; i < outlines.size(); ++i) {
    Body body;
    body.name = "body" + std::to_string(i);
    body.material = "sand";
    body.material_index = 0;
    body.outline = std::move(outlines[i]);
    make_counter_clockwise(body.outline);
    bounding_box(body.outline, body.min, body.max);
    scene.bodies.push_back(body);
  }
  return scene;
}

double sum(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

/// Rounding bound of a sum of n positive terms, n eps |total|: the count and each particle's
/// dp^2 are exact, only the floating-point addition of the totals is not.
double summation_bound(std::size_t n, double total) {
  return static_cast<double>(n) * std::numeric_limits<double>::epsilon() * total;
}

std::vector<Vec2> rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

TEST(Lattice, RectangleCountMassAndVolumeAreExact) {
  // Peng 2015 5.2 column: 0.2 m x 0.1 m at dp = 2 mm -> 100 x 50 particles.
  const Scene scene = scene_with(0.002, 1850.0, {rectangle(0.0, 0.0, 0.2, 0.1)});
  const Particles p = sample_bodies(scene);
  ASSERT_EQ(p.size(), 5000u);
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(p.volume[i], 0.002 * 0.002);
  EXPECT_NEAR(sum(p.volume), 0.02, summation_bound(p.size(), 0.02));
  EXPECT_NEAR(sum(p.mass), 1850.0 * 0.02, summation_bound(p.size(), 1850.0 * 0.02));
}

TEST(Lattice, ARectangleTheSpacingDoesNotDivideIsNamedWithWhatTheLatticeSamples) {
  // The column 0.2 x 0.1 m: 2 mm divides both sides; 3.5 mm (57.14 x 28.57 spacings) keeps 57
  // columns (0.1995 m, 0.5 mm short of max x) and 29 rows (0.1015 m, 1.5 mm beyond max y).
  EXPECT_TRUE(lattice_misfits(scene_with(0.002, 1850.0, {rectangle(0.0, 0.0, 0.2, 0.1)})).empty());
  const Scene column = scene_with(0.0035, 1850.0, {rectangle(0.0, 0.0, 0.2, 0.1)});
  const std::vector<std::string> lines = lattice_misfits(column);
  ASSERT_EQ(lines.size(), 1u);
  const std::string& line = lines[0];
  EXPECT_NE(line.find("body.body0"), std::string::npos) << line;
  EXPECT_NE(line.find("last column ends 0.0005 m short of max x"), std::string::npos) << line;
  EXPECT_NE(line.find("last row ends 0.0015 m beyond max y"), std::string::npos) << line;
  EXPECT_NE(line.find("0.1995 x 0.1015 m"), std::string::npos) << line;
  // What the lattice samples is what the line says: 57 x 29 particles.
  const Particles p = sample_bodies(column);
  EXPECT_EQ(p.size(), 57u * 29u);
  double top = 0.0;
  for (const Vec2& x : p.position) top = std::max(top, x.y());
  EXPECT_NEAR(top + 0.5 * 0.0035, 0.1015, 1e-12);
  // A 7.5 m block at dp 0.2 (37.5 spacings): its top row ends a half spacing short of the top.
  const std::vector<std::string> block =
      lattice_misfits(scene_with(0.2, 1800.0, {rectangle(0.0, -2.5, 7.5, 5.0)}));
  ASSERT_EQ(block.size(), 1u);
  EXPECT_NE(block[0].find("last column ends 0.1 m short of max x"), std::string::npos) << block[0];
  EXPECT_NE(block[0].find("last row ends 0.1 m short of max y = 5"), std::string::npos) << block[0];
  // Sides of exactly k dp that floating point misses by an ulp, and polygons, are not named.
  EXPECT_TRUE(lattice_misfits(scene_with(0.1, 1800.0, {rectangle(0.0, 0.0, 0.3, 0.7)})).empty());
  Scene polygon = scene_with(0.0035, 1850.0, {rectangle(0.0, 0.0, 0.2, 0.1)});
  polygon.bodies[0].shape = ShapeKind::polygon;
  EXPECT_TRUE(lattice_misfits(polygon).empty());
}

TEST(Lattice, ParticlesSitAtCellCentresInsideTheBody) {
  const Scene scene = scene_with(0.1, 1000.0, {rectangle(1.0, 2.0, 1.5, 2.3)});
  const Particles p = sample_bodies(scene);
  double x_min = 1e9, y_max = -1e9;
  for (const Vec2& x : p.position) {
    x_min = std::min(x_min, x.x());
    y_max = std::max(y_max, x.y());
  }
  EXPECT_NEAR(x_min, 1.05, 1e-12);
  EXPECT_NEAR(y_max, 2.25, 1e-12);
  EXPECT_EQ(p.size(), 15u);
  EXPECT_DOUBLE_EQ(p.volume[0], 0.01);
  EXPECT_DOUBLE_EQ(p.mass[0], 10.0);
  EXPECT_DOUBLE_EQ(p.density[0], 1000.0);
}

TEST(Lattice, ClockwiseLShapedPolygonCountMassAndVolumeAreExact) {
  // An L: [0, 0.2] x [0, 0.2] without [0.1, 0.2] x [0.1, 0.2], area 0.03,
  // given clockwise; at dp = 0.01 that is 400 - 100 = 300 cells.
  std::vector<Vec2> l_shape = {{0, 0}, {0, 0.2}, {0.1, 0.2}, {0.1, 0.1}, {0.2, 0.1}, {0.2, 0}};
  const Scene scene = scene_with(0.01, 2000.0, {l_shape});
  const Particles p = sample_bodies(scene);
  ASSERT_EQ(p.size(), 300u);
  EXPECT_NEAR(sum(p.volume), 0.03, summation_bound(p.size(), 0.03));
  EXPECT_NEAR(sum(p.mass), 60.0, summation_bound(p.size(), 60.0));
  for (const Vec2& x : p.position) EXPECT_FALSE(x.x() > 0.1 && x.y() > 0.1);
}

TEST(Lattice, SlantedEdgeVolumeErrorStaysWithinHalfACellPerEdgeCell) {
  // The Griffiths & Lane slope outline at dp = 0.25 m: the 2:1 face cuts cells; the midpoint
  // rule keeps the volume within dp * (slanted edge length) / 2 of the area (220 m^2).
  const double dp = 0.25;
  const Scene scene = scene_with(dp, 2000.0, {{{0, 0}, {32, 0}, {12, 10}, {0, 10}}});
  const Particles p = sample_bodies(scene);
  const double area = 220.0;
  const double face = std::hypot(20.0, 10.0);
  EXPECT_LT(std::abs(sum(p.volume) - area), 0.5 * dp * face);
}

TEST(Lattice, TouchingBodiesShareNoParticleAndKeepTheirIndices) {
  const Scene scene = scene_with(0.1, 1000.0, {rectangle(0, 0, 1, 0.5), rectangle(0, 0.5, 1, 1)});
  const Particles p = sample_bodies(scene);
  std::set<std::pair<long, long>> cells;
  for (const Vec2& x : p.position) {
    cells.insert({std::lround(x.x() / 0.05), std::lround(x.y() / 0.05)});
  }
  EXPECT_EQ(p.size(), 100u);
  EXPECT_EQ(cells.size(), p.size());
  EXPECT_EQ(std::count(p.body.begin(), p.body.end(), 1), 50);
  EXPECT_EQ(std::count(p.material.begin(), p.material.end(), 0), 100);
}

/// A quarter annulus r0 <= r <= r1 about the origin, its arcs as `chords` chords each.
std::vector<Vec2> quarter_annulus(double r0, double r1, int chords) {
  std::vector<Vec2> outline;
  for (int k = 0; k <= chords; ++k) {
    const double a = 0.5 * std::numbers::pi * k / chords;
    outline.emplace_back(r1 * std::cos(a), r1 * std::sin(a));
  }
  for (int k = chords; k >= 0; --k) {
    const double a = 0.5 * std::numbers::pi * k / chords;
    outline.emplace_back(r0 * std::cos(a), r0 * std::sin(a));
  }
  return outline;
}

TEST(Lattice, PolarRingsFillAQuarterAnnulusExactlyAndSitHalfASpacingOffEverySide) {
  // The cavity's soil: 1 m <= r <= 3 m at dp 0.1, arcs as 64 chords (inside the circles by at
  // most 3 (1 - cos(pi / 256)) = 0.2 mm: every ring point stays inside the outline).
  const double dp = 0.1;
  Scene scene = scene_with(dp, 1800.0, {quarter_annulus(1.0, 3.0, 64)});
  scene.bodies[0].lattice = LatticeKind::polar;
  const Particles p = sample_bodies(scene);
  const double area = 0.25 * std::numbers::pi * (9.0 - 1.0);
  EXPECT_NEAR(sum(p.volume), area, 1e-12 * area);  // the midpoint rule in r is exact here
  EXPECT_NEAR(sum(p.mass), 1800.0 * area, 1e-12 * 1800.0 * area);
  std::size_t expected = 0;
  double nearest_cavity = 1e9, nearest_x_axis = 1e9, nearest_y_axis = 1e9;
  for (int k = 0; k < 20; ++k) {
    const double r = 1.0 + (k + 0.5) * dp;
    const long n = 4 * std::lround(0.5 * std::numbers::pi * r / dp);
    expected += static_cast<std::size_t>(n / 4);
    nearest_x_axis = std::min(nearest_x_axis, r * std::sin(std::numbers::pi / n));
  }
  ASSERT_EQ(p.size(), expected);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2 x = p.position[i];
    nearest_cavity = std::min(nearest_cavity, x.norm() - 1.0);
    nearest_y_axis = std::min(nearest_y_axis, x.x());
    // Every point's arc spacing within 10 % of dp: a near-uniform cloud.
    const double r = x.norm();
    const double arc = p.volume[i] / dp;
    EXPECT_NEAR(arc, dp, 0.1 * dp) << "at r = " << r;
  }
  EXPECT_NEAR(nearest_cavity, 0.5 * dp, 1e-12);
  EXPECT_NEAR(nearest_y_axis, nearest_x_axis, 1e-12);  // the quarter is symmetric about y = x
  EXPECT_GT(nearest_x_axis, 0.45 * dp);
  EXPECT_LT(nearest_x_axis, 0.5 * dp + 1e-12);
}

TEST(Lattice, ParticlesStartWithTheBodyInitialVelocityAndNoStress) {
  Scene scene = scene_with(0.1, 1000.0, {rectangle(0, 0, 1, 0.1)});
  scene.bodies[0].initial_velocity = Vec2(0.01, 0.0);
  const Particles p = sample_bodies(scene);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p.velocity[i], Vec2(0.01, 0.0));
    EXPECT_EQ(p.stress[i], Mat3::Zero());
  }
}

}  // namespace
}  // namespace duet
