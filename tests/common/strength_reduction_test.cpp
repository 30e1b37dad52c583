// Peng's order of strength reduction (common/strength_reduction.hpp): gravity loading at full
// strength, then c / f and tan(phi) / f reached over the run's first `ramp` seconds.

#include "common/strength_reduction.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "benchmarks/scene_input.hpp"
#include "common/input_error.hpp"

namespace duet {
namespace {

const std::string kSlope = R"(name = "block"
spacing = 0.5
gravity = [0.0, -9.81]

[time]
end_time = 5.0

[initial_stress]
kind = "gravity-loading"
damping = 20.0
time = 2.0

[material.soil]
model = "drucker-prager"
density = 2000.0
E = 1.0e8
nu = 0.3
phi = 20.0
psi = 0.0
c = 10.0e3

[body.soil]
material = "soil"
min = [0.0, 0.0]
max = [4.0, 2.0]

[wall.base]
points = [[0.0, 0.0], [6.0, 0.0]]
)";

Scene slope(std::vector<std::string> overrides, std::string text = kSlope) {
  return load_scene_checked_from_string(text, "block.toml", overrides);
}

/// The block with a geostatic initial stress instead of gravity loading.
std::string geostatic() {
  std::string text = kSlope;
  const std::string loading = "kind = \"gravity-loading\"\ndamping = 20.0\ntime = 2.0";
  text.replace(text.find(loading), loading.size(), "kind = \"geostatic\"\nK0 = 0.5");
  return text;
}

std::string refusal(std::vector<std::string> overrides) {
  try {
    slope(overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

double c_of(const std::map<std::string, ParameterValue>& p) {
  return std::get<double>(p.at("c"));
}
double phi_of(const std::map<std::string, ParameterValue>& p) {
  return std::get<double>(p.at("phi"));
}

TEST(StrengthReduction, AfterLoadingTheSoilSettlesAtFullStrengthAndTheFactorRampsToF) {
  const Scene s = slope({"strength_reduction.factor=1.5", "strength_reduction.ramp=2"});
  EXPECT_EQ(s.strength_reduction.stage, "after-loading");  // Peng's order is the default
  EXPECT_TRUE(strength_changes_in_run(s));
  EXPECT_DOUBLE_EQ(loading_strength_factor(s), 1.0);
  EXPECT_DOUBLE_EQ(strength_factor_at(s, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(strength_factor_at(s, 1.0), 1.25);
  EXPECT_DOUBLE_EQ(strength_factor_at(s, 2.0), 1.5);
  EXPECT_DOUBLE_EQ(strength_factor_at(s, 4.0), 1.5);
  // At once without a ramp
  const Scene at_once = slope({"strength_reduction.factor=1.5"});
  EXPECT_DOUBLE_EQ(strength_factor_at(at_once, 0.0), 1.0);  // as loaded
  EXPECT_DOUBLE_EQ(strength_factor_at(at_once, 1e-9), 1.5);
}

TEST(StrengthReduction, ThroughoutAndWithoutGravityLoadingTheReducedStrengthHoldsFromTheStart) {
  for (const Scene& s :
       {slope({"strength_reduction.factor=1.5", "strength_reduction.stage=throughout"}),
        slope({"strength_reduction.factor=1.5"}, geostatic())}) {
    EXPECT_FALSE(strength_changes_in_run(s));
    EXPECT_DOUBLE_EQ(loading_strength_factor(s), 1.5);
    EXPECT_DOUBLE_EQ(strength_factor_at(s, 0.0), 1.5);
  }
}

TEST(StrengthReduction, ParametersAtAFactorAreTheFullStrengthOnesReduced) {
  const double deg = std::numbers::pi / 180.0;
  const Scene s = slope({"strength_reduction.factor=1.5", "strength_reduction.ramp=2"});
  const Material& m = s.materials[0];
  // Full strength for gravity loading
  EXPECT_DOUBLE_EQ(c_of(parameters_at(s, m, 1.0)), 10.0e3);
  EXPECT_DOUBLE_EQ(phi_of(parameters_at(s, m, 1.0)), 20.0);
  // Part way: c / f' and tan phi / f' (Peng eq 39, Griffiths & Lane)
  EXPECT_NEAR(c_of(parameters_at(s, m, 1.25)), 8.0e3, 1e-9);
  EXPECT_NEAR(std::tan(phi_of(parameters_at(s, m, 1.25)) * deg), std::tan(20.0 * deg) / 1.25,
              1e-12);
  // At the scene's factor: the parameters as loaded, bit for bit
  EXPECT_EQ(parameters_at(s, m, 1.5), m.parameters);
  // Peng's eq 40 with rule = "angle"
  const Scene angle = slope({"strength_reduction.factor=2", "strength_reduction.rule=angle"});
  EXPECT_NEAR(phi_of(parameters_at(angle, angle.materials[0], 1.6)), 12.5, 1e-12);
}

TEST(StrengthReduction, ARampThatChangesNothingOrOutlastsTheRunIsRefused) {
  EXPECT_NE(refusal({"strength_reduction.factor=1.5", "strength_reduction.stage=throughout",
                     "strength_reduction.ramp=1"})
                .find("strength_reduction.ramp"),
            std::string::npos);
  EXPECT_NE(refusal({"strength_reduction.factor=1.5", "strength_reduction.ramp=5"})
                .find("before time.end_time"),
            std::string::npos);
  EXPECT_NE(refusal({"strength_reduction.ramp=-1"}).find("strength_reduction.ramp"),
            std::string::npos);
  EXPECT_NE(refusal({"strength_reduction.stage=before"}).find("strength_reduction.stage"),
            std::string::npos);
}

}  // namespace
}  // namespace duet
