// Phase timers: accumulation per phase, the scoped guard, JSON for metrics.json. A fake clock is
// injected, so nothing sleeps and nothing depends on machine speed.

#include "common/timers.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace duet {
namespace {

/// A clock that only moves when the test says so.
struct FakeClock {
  std::shared_ptr<double> now = std::make_shared<double>(100.0);
  Timers::Clock clock() const {
    return [now = now] { return *now; };
  }
  void advance(double seconds) const { *now += seconds; }
};

TEST(Timers, ScopedTimerChargesTheElapsedTimeToItsPhase) {
  // Arrange
  const FakeClock clock;
  Timers timers(clock.clock());
  // Act
  {
    ScopedTimer t(timers, Phase::forces);
    clock.advance(0.25);
  }
  // Assert
  EXPECT_DOUBLE_EQ(timers.seconds(Phase::forces), 0.25);
  EXPECT_EQ(timers.count(Phase::forces), 1);
  EXPECT_EQ(timers.seconds(Phase::neighbours), 0.0);
}

TEST(Timers, RepeatedScopesAccumulateAndPhasesStaySeparate) {
  // Arrange
  const FakeClock clock;
  Timers timers(clock.clock());
  // Act: three steps of neighbours (0.1 s) then constitutive (0.3 s), with untimed gaps.
  for (int step = 0; step < 3; ++step) {
    {
      ScopedTimer t(timers, Phase::neighbours);
      clock.advance(0.1);
    }
    clock.advance(5.0);  // outside any timer
    {
      ScopedTimer t(timers, Phase::constitutive);
      clock.advance(0.3);
    }
  }
  // Assert
  EXPECT_NEAR(timers.seconds(Phase::neighbours), 0.3, 1e-12);
  EXPECT_NEAR(timers.seconds(Phase::constitutive), 0.9, 1e-12);
  EXPECT_EQ(timers.count(Phase::neighbours), 3);
  EXPECT_NEAR(timers.total_seconds(), 1.2, 1e-12);
}

TEST(Timers, StopChargesOnceAndTheEndOfScopeAddsNothingMore) {
  // Arrange
  const FakeClock clock;
  Timers timers(clock.clock());
  // Act
  {
    ScopedTimer t(timers, Phase::solve);
    clock.advance(2.0);
    t.stop();
    clock.advance(7.0);
  }
  // Assert
  EXPECT_DOUBLE_EQ(timers.seconds(Phase::solve), 2.0);
  EXPECT_EQ(timers.count(Phase::solve), 1);
}

TEST(Timers, AddingAnotherSetSumsEveryPhase) {
  // Arrange
  Timers solver;
  Timers output;
  solver.add(Phase::mesh, 1.5);
  output.add(Phase::output, 0.5);
  output.add(Phase::mesh, 0.25);
  // Act
  solver.add(output);
  // Assert
  EXPECT_DOUBLE_EQ(solver.seconds(Phase::mesh), 1.75);
  EXPECT_DOUBLE_EQ(solver.seconds(Phase::output), 0.5);
  EXPECT_EQ(solver.count(Phase::mesh), 2);
}

TEST(Timers, JsonNamesEveryPhaseWithItsSeconds) {
  // Arrange
  Timers timers;
  timers.add(Phase::neighbours, 1.0);
  timers.add(Phase::solve, 3.0);
  // Act
  const Json j = timers.to_json();
  // Assert: the names of metrics.json "timing" (DESIGN.md), zero for phases not timed.
  for (const char* name : {"neighbours", "constitutive", "forces", "mesh", "solve", "output"}) {
    ASSERT_NE(j.find(name), nullptr) << name;
  }
  EXPECT_DOUBLE_EQ(j.find("neighbours")->number(), 1.0);
  EXPECT_DOUBLE_EQ(j.find("solve")->number(), 3.0);
  EXPECT_DOUBLE_EQ(j.find("forces")->number(), 0.0);
  EXPECT_EQ(j.members().size(), n_phases);
}

TEST(Timers, RealClockIsMonotonic) {
  // Arrange
  Timers timers;
  // Act
  const double a = timers.now();
  {
    ScopedTimer t(timers, Phase::other);
    volatile double sink = 0.0;
    for (int i = 0; i < 1000; ++i) sink = sink + i;
  }
  const double b = timers.now();
  // Assert: no thresholds, only ordering.
  EXPECT_LE(a, b);
  EXPECT_GE(timers.seconds(Phase::other), 0.0);
  EXPECT_LE(timers.seconds(Phase::other), b - a);
}

}  // namespace
}  // namespace duet
