// Kinetic energy of the particles and the record of its peak over a run (metrics.json
// "kinetic_energy"): the collapse benchmarks' "at rest" criterion.
#include "common/kinetic_energy.hpp"

#include <gtest/gtest.h>

namespace duet {
namespace {

TEST(KineticEnergy, IsHalfTheSumOfMassTimesSpeedSquared) {
  // Arrange: two particles, 2 kg/m at (3, 4) m/s and 0.5 kg/m at (0, -2) m/s
  Particles p;
  p.resize(2);
  p.mass = {2.0, 0.5};
  p.velocity = {Vec2(3.0, 4.0), Vec2(0.0, -2.0)};
  // Act, Assert: 0.5 (2 * 25 + 0.5 * 4) = 26 J/m
  EXPECT_DOUBLE_EQ(kinetic_energy(p), 26.0);
}

TEST(KineticEnergyRecord, KeepsThePeakAndItsTimeAndTheLastValue) {
  // Arrange: energy rising to 4 J/m at t = 0.2 s, then decaying
  KineticEnergyRecord r;
  // Act
  r.record(0.0, 0.0);
  r.record(0.1, 1.0);
  r.record(0.2, 4.0);
  r.record(0.3, 2.0);
  r.record(0.4, 1.0e-6);
  // Assert
  EXPECT_DOUBLE_EQ(r.peak, 4.0);
  EXPECT_DOUBLE_EQ(r.peak_time, 0.2);
  EXPECT_DOUBLE_EQ(r.end, 1.0e-6);
  EXPECT_DOUBLE_EQ(r.end_over_peak(), 2.5e-7);
}

TEST(KineticEnergyRecord, ARunThatNeverMovesHasARatioOfZero) {
  KineticEnergyRecord r;
  r.record(0.0, 0.0);
  r.record(1.0, 0.0);
  EXPECT_EQ(r.end_over_peak(), 0.0);
}

TEST(KineticEnergyCarriers, TheFewestParticlesCarryingHalfAndTheOneCarryingMost) {
  // Arrange: kinetic energies 0.5 m v^2 = 1, 9, 1, 1 J/m (total 12): the second alone carries
  // more than half
  Particles p;
  p.resize(4);
  p.mass = {2.0, 2.0, 2.0, 2.0};
  p.velocity = {Vec2(1.0, 0.0), Vec2(0.0, -3.0), Vec2(-1.0, 0.0), Vec2(0.0, 1.0)};
  p.position = {Vec2(0.0, 0.0), Vec2(0.5, 0.25), Vec2(1.0, 0.0), Vec2(2.0, 0.0)};
  // Act
  const KineticEnergyCarriers one = kinetic_energy_carriers(p);
  p.velocity[1] = Vec2(0.0, 1.0);  // now 1 J/m each: two of four carry half
  const KineticEnergyCarriers spread = kinetic_energy_carriers(p);
  // Assert
  EXPECT_EQ(one.half, 1u);
  EXPECT_EQ(one.largest, 1u);
  EXPECT_DOUBLE_EQ(one.speed, 3.0);
  EXPECT_EQ(one.position, Vec2(0.5, 0.25));
  EXPECT_EQ(spread.half, 2u);
}

TEST(KineticEnergyCarriers, NoneWhenNothingMoves) {
  Particles p;
  p.resize(3);
  p.mass = {1.0, 1.0, 1.0};
  EXPECT_EQ(kinetic_energy_carriers(p).half, 0u);
  EXPECT_EQ(kinetic_energy_carriers(Particles{}).half, 0u);
}

}  // namespace
}  // namespace duet
