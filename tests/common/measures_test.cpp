// Measures (common/measures.cpp): period from zero crossings, the run-out toe with a minimum
// thickness, and the reduction of a series to the scored value.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/measures.hpp"

namespace duet {
namespace {

TEST(Measures, AnAxisymmetricWallStressDividesByTheVectorAreaTheWallSweeps) {
  // A flat disc of radius R swept by the segment (0, z) - (R, z): pi R^2, along the axis
  EXPECT_NEAR(wall_vector_area({Vec2(0.0, 1.0), Vec2(2.0, 1.0)}, Formulation::axisymmetric),
              std::numbers::pi * 4.0, 1e-12);
  // A hemisphere of radius a (a quarter arc from the equator to the axis): the vector area is
  // (int n_r dA, int n_z dA) = (pi^2 a^2 / 2, pi a^2), so a uniform pressure p on it gives a
  // reaction of p times its magnitude; 2,000 chords approach it to O(1 / n^2)
  std::vector<Vec2> arc;
  for (int i = 0; i <= 2000; ++i) {
    const double angle = 0.5 * std::numbers::pi * i / 2000.0;
    arc.emplace_back(std::cos(angle), std::sin(angle));
  }
  const double hemisphere = std::numbers::pi * std::hypot(0.5 * std::numbers::pi, 1.0);
  EXPECT_NEAR(wall_vector_area(arc, Formulation::axisymmetric), hemisphere, 1e-6 * hemisphere);
  // A wall drawn across the axis sweeps only its part at r >= 0
  EXPECT_NEAR(wall_vector_area({Vec2(1.5, 1.0), Vec2(-0.1, 1.0)}, Formulation::axisymmetric),
              std::numbers::pi * 2.25, 1e-12);
  // Plane strain: the chord
  EXPECT_NEAR(wall_vector_area(arc, Formulation::plane_strain), std::sqrt(2.0), 1e-12);
}

TEST(PeriodFromZeroCrossings, RecoversThePeriodOfASampledSine) {
  const double period = 0.04;
  std::vector<double> t, v;
  for (int k = 0; k <= 1000; ++k) {
    t.push_back(k * 1e-4);
    v.push_back(std::cos(2.0 * std::numbers::pi * t.back() / period));
  }
  EXPECT_NEAR(period_from_zero_crossings(t, v), period, 1e-6);
}

TEST(PeriodFromZeroCrossings, IsUndefinedBeforeTwoCrossings) {
  EXPECT_TRUE(std::isnan(period_from_zero_crossings({0.0, 1.0, 2.0}, {1.0, -1.0, -2.0})));
}

Particles column_of_particles(const std::vector<Vec2>& positions) {
  Particles p;
  p.resize(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    p.position[i] = positions[i];
    p.body[i] = 0;
  }
  return p;
}

TEST(FrontPosition, IgnoresColumnsThinnerThanTheMinimumThickness) {
  // Two columns 3 particles thick at x = 0.005, 0.015 and a lone particle at x = 0.045.
  const Particles p = column_of_particles({{0.005, 0.005},
                                           {0.005, 0.015},
                                           {0.005, 0.025},
                                           {0.015, 0.005},
                                           {0.015, 0.015},
                                           {0.015, 0.025},
                                           {0.045, 0.005}});
  EXPECT_DOUBLE_EQ(front_position(p, 0, 0.01, 0.01, 0.0), 0.045);
  EXPECT_DOUBLE_EQ(front_position(p, 0, 0.01, 0.01, 0.03), 0.015);
}

TEST(FrontPosition, ADepthInMetresCountsTheSameMaterialAtEverySpacing) {
  // A deposit 2 cm deep from x = 0 to 0.1 m and a thin part from 0.1 to 0.2 m (rows below
  // 7.5 mm: one at dp 5 mm, three at dp 2.5 mm): with a depth of 1 cm over 2 cm columns its toe
  // is at the deep part's end at both spacings, where "3 spacings" moves with dp.
  for (const double dp : {0.005, 0.0025}) {
    std::vector<Vec2> positions;
    for (double x = 0.5 * dp; x < 0.2; x += dp) {
      const double depth = x < 0.1 ? 0.02 : 0.0075;
      for (double y = 0.5 * dp; y < depth; y += dp) positions.emplace_back(x, y);
    }
    const Particles p = column_of_particles(positions);
    EXPECT_NEAR(front_position(p, 0, dp, 0.02, 0.01), 0.1 - 0.5 * dp, 1e-12) << dp;
    // the lattice column and "3 spacings": the thin part counts once 3 dp fit in it
    const double toe = front_position(p, 0, dp, dp, 3.0 * dp);
    EXPECT_NEAR(toe, dp < 0.004 ? 0.2 - 0.5 * dp : 0.1 - 0.5 * dp, 1e-12) << dp;
  }
}

TEST(FrontPosition, AColumnOfLooseParticlesShorterThanTheDepthDoesNotCount) {
  // Five particles scattered over one 2 cm column at dp 2 mm hold 1 mm of material spread
  // over it: below 1 cm, so the toe stays at the deep part's end (x = 0.019); three of them in
  // one 2 mm lattice column make "3 spacings" and move the toe 8 cm on.
  std::vector<Vec2> positions;
  const double dp = 0.002;
  for (double x = 0.001; x < 0.02; x += dp) {
    for (double y = 0.001; y < 0.02; y += dp) positions.emplace_back(x, y);
  }
  for (const Vec2 loose : {Vec2(0.0995, 0.001), Vec2(0.0985, 0.004), Vec2(0.0991, 0.009),
                           Vec2(0.092, 0.001), Vec2(0.085, 0.002)}) {
    positions.push_back(loose);
  }
  const Particles p = column_of_particles(positions);
  EXPECT_NEAR(front_position(p, 0, dp, 0.02, 0.01), 0.019, 1e-12);
  EXPECT_NEAR(front_position(p, 0, dp, dp, 3.0 * dp), 0.0995, 1e-12);
}

TEST(EvaluateMeasure, ExpansionIsTheRadialWallsRadiusOverItsFirst) {
  // A quarter-circle cavity wall of radius 0.5 about (1, 2), its radial speed rising linearly
  // from 0.1 to 0.3 m/s over 2 s, then held: at t = 4 s its radius is 0.5 + 0.4 + 0.6 = 1.5 m.
  Scene scene;
  Wall wall;
  wall.name = "cavity";
  wall.radial = true;
  wall.centre = Vec2(1.0, 2.0);
  for (int k = 0; k <= 8; ++k) {
    const double angle = 0.5 * std::numbers::pi * k / 8.0;
    wall.points.push_back(wall.centre + 0.5 * Vec2(std::cos(angle), std::sin(angle)));
  }
  wall.radial_velocity = {{0.0, {0.1, 0.0}}, {2.0, {0.3, 0.0}}};
  scene.walls.push_back(wall);
  Measure m;
  m.kind = MeasureKind::expansion;
  m.target = "cavity";
  EXPECT_NEAR(evaluate_measure(m, scene, Particles{}, {}, 0.0), 1.0, 1e-14);
  EXPECT_NEAR(evaluate_measure(m, scene, Particles{}, {}, 4.0), 3.0, 1e-12);
}

/// A scene of one body "b" (dp 0.01), for the recorder's tests.
Scene scene_of_body_b() {
  Scene scene;
  scene.spacing = 0.01;
  Body body;
  body.name = "b";
  scene.bodies.push_back(body);
  return scene;
}

/// The largest x displacement in body "b", taken `at`.
Measure displacement_measure(const char* name, MeasureAt at) {
  Measure m;
  m.name = name;
  m.kind = MeasureKind::max_displacement;
  m.target = "b";
  m.component = "x";
  m.at = at;
  return m;
}

TEST(MeasureRecorder, MaxTakesTheLargestMagnitudeAndTimeInterpolates) {
  Scene scene = scene_of_body_b();
  const Measure peak = displacement_measure("peak", MeasureAt::max);
  Measure half = displacement_measure("half", MeasureAt::time);
  half.time = 0.5;
  scene.measures = {peak, half};
  MeasureRecorder recorder(scene);
  Particles p = column_of_particles({{0.0, 0.0}});
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.1 * k;
    p.displacement[0] = Vec2(std::sin(std::numbers::pi * t), 0.0);  // peak 1 at t = 0.5
    recorder.sample(t, p, {});
  }
  EXPECT_NEAR(recorder.final_value("peak"), 1.0, 1e-12);
  EXPECT_NEAR(recorder.final_value("half"), 1.0, 1e-12);
}

TEST(MeasureRecorder, AWindowAtATimeTakesTheMeanThroughTheRinging) {
  // A ramp 1 + t with a ringing of amplitude 0.2 and period 0.2 s on it, sampled every 0.01 s;
  // at t = 0.55 the ringing is at its trough: the value there is 1.35, the ramp's 1.55
  Scene scene = scene_of_body_b();
  Measure plain = displacement_measure("plain", MeasureAt::time);
  plain.time = 0.55;
  Measure windowed = plain;
  windowed.name = "windowed";
  windowed.window = 0.2;  // one period
  scene.measures = {plain, windowed};
  MeasureRecorder recorder(scene);
  Particles p = column_of_particles({{0.0, 0.0}});
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.01 * k;
    p.displacement[0] = Vec2(1.0 + t + 0.2 * std::sin(2.0 * std::numbers::pi * t / 0.2), 0.0);
    recorder.sample(t, p, {});
  }
  EXPECT_NEAR(recorder.final_value("plain"), 1.35, 1e-9);
  // 20 or 21 samples over one period: the ringing cancels but for one end sample, 0.2 / 21
  EXPECT_NEAR(recorder.final_value("windowed"), 1.55, 0.2 / 21.0 + 1e-12);
}

TEST(MeasureRecorder, AFactorOfSafetyIsNotScoredByOneRunAndTheOtherReferencesAre) {
  // A slope run at strength reduction factor 1.2: its safety_factor measure is that factor, which
  // says nothing against the slope's factor of safety (found by duet srf); its displacement is
  // scored as usual.
  Scene scene;
  scene.spacing = 0.5;
  scene.strength_reduction.factor = 1.2;
  Body body;
  body.name = "slope";
  scene.bodies.push_back(body);
  Measure factor;
  factor.name = "safety_factor";
  factor.kind = MeasureKind::safety_factor;
  Measure moved;
  moved.name = "moved";
  moved.kind = MeasureKind::max_displacement;
  moved.target = "slope";
  moved.component = "x";
  scene.measures = {factor, moved};
  scene.references = {{"safety_factor", 1.4, "Griffiths & Lane 1999", 0.1},
                      {"moved", 0.5, "a closed form", 0.1}};
  MeasureRecorder recorder(scene);
  Particles p = column_of_particles({{0.0, 0.0}});
  p.displacement[0] = Vec2(0.4, 0.0);
  recorder.sample(0.0, p, {});
  // Act
  const Json accuracy = recorder.accuracy();
  // Assert
  EXPECT_EQ(accuracy.find("safety_factor"), nullptr);
  EXPECT_NEAR(recorder.final_value("safety_factor"), 1.2, 1e-15);  // still recorded
  ASSERT_NE(accuracy.find("moved"), nullptr);
  EXPECT_NEAR(accuracy.find("moved")->find("rel_error")->number(), 0.2, 1e-12);
}

TEST(MaterialPointDisplacement, IsExactForALinearFieldAtABeamTipWhereNoParticleSits) {
  // A beam 1 m x 0.1 m sampled at dp 0.0125 (cell centres: no particle at mid-depth, none at
  // x = 1), displaced by u = (0.01 - 0.2 y, 0.05 + 0.3 x - 0.1 y): at its tip's mid-depth
  // (1, 0.05) the displacement is (0, 0.345).
  const double dp = 0.0125;
  std::vector<Vec2> start;
  for (double x = 0.5 * dp; x < 1.0; x += dp) {
    for (double y = 0.5 * dp; y < 0.1; y += dp) start.emplace_back(x, y);
  }
  Particles p = column_of_particles(start);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2 X = start[i];
    p.displacement[i] = Vec2(0.01 - 0.2 * X.y(), 0.05 + 0.3 * X.x() - 0.1 * X.y());
    p.position[i] = X + p.displacement[i];
  }
  const Vec2 u = material_point_displacement(p, 0, Vec2(1.0, 0.05), 2.0 * dp);
  EXPECT_NEAR(u.x(), 0.0, 1e-13);
  EXPECT_NEAR(u.y(), 0.345, 1e-13);
  // The largest displacement is a corner particle's, not the centreline's.
  double largest = 0.0;
  for (const Vec2& d : p.displacement) largest = std::max(largest, std::abs(d.y()));
  EXPECT_GT(largest - u.y(), 0.0);
  // Away from the body: no particle, no value.
  EXPECT_TRUE(std::isnan(material_point_displacement(p, 0, Vec2(2.0, 0.05), 2.0 * dp).y()));
}

}  // namespace
}  // namespace duet
