// The end-of-run warnings read from a method's diagnostics: each fires above its threshold and
// not at it, and the energy drift only where the energy must be conserved.
#include "benchmarks/run_warnings.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

#include "benchmarks/methods.hpp"
#include "benchmarks/scene_input.hpp"
#include "tests/benchmarks/child_run.hpp"

namespace duet {
namespace {

// Linear-elastic, no gravity, a fixed floor: its energy must be conserved.
const char* kElasticBlock = R"(
spacing = 0.1
[time]
end_time = 1.0
[material.steel]
model = "linear-elastic"
density = 7800.0
E = 2e11
nu = 0.3
[body.block]
material = "steel"
min = [0.0, 0.0]
max = [1.0, 1.0]
initial_velocity = [1.0, 0.0]
[wall.floor]
points = [[-1.0, 0.0], [2.0, 0.0]]
)";

std::vector<std::string> warnings_for(const Json& diagnostics,
                                      const std::vector<std::string>& overrides = {}) {
  const Scene scene = load_scene_checked_from_string(kElasticBlock, "block.toml", overrides);
  KineticEnergyRecord energy;  // never moved: no kinetic energy warning
  const EnergyBudget budget(scene, Particles{}, 0.0);
  return run_warnings(scene, /*inertial=*/true, energy, budget, 1.0, diagnostics, 100);
}

Json with(const std::string& key, double value) {
  Json j = Json::object();
  j[key] = value;
  return j;
}

bool says(const std::vector<std::string>& warnings, const std::string& start) {
  for (const std::string& w : warnings) {
    if (w.rfind(start, 0) == 0) return true;
  }
  return false;
}

TEST(RunWarnings, AnyPenetrationIsReported) {
  Json d = with("penetrations_max", 3.0);
  d["penetrations_last_step"] = 1.0;
  d["penetrations_total"] = 250.0;
  const auto w = warnings_for(d);
  ASSERT_TRUE(says(w, "penetrations: up to 3 particles (3 %)")) << (w.empty() ? "" : w[0]);
  EXPECT_NE(w[0].find("250 particle-steps"), std::string::npos) << w[0];
  EXPECT_TRUE(warnings_for(with("penetrations_max", 0.0)).empty());
}

TEST(RunWarnings, IsolatedNodesAboveFivePercent) {
  EXPECT_TRUE(says(warnings_for(with("isolated_nodes_max", 6.0)), "isolated nodes: up to 6"));
  EXPECT_TRUE(warnings_for(with("isolated_nodes_max", 5.0)).empty());
}

TEST(RunWarnings, EnergyDriftOnlyWhereEnergyIsConserved) {
  EXPECT_TRUE(says(warnings_for(with("energy_drift_max", 0.03)), "energy drift: "));
  EXPECT_TRUE(warnings_for(with("energy_drift_max", 0.02)).empty());
  // Gravity works on the block, damping takes energy out: a drift says nothing.
  EXPECT_TRUE(warnings_for(with("energy_drift_max", 0.5), {"gravity=[0.0, -9.81]"}).empty());
  EXPECT_TRUE(warnings_for(with("energy_drift_max", 0.5), {"spfem.damping=1.0"}).empty());
}

TEST(RunWarnings, StepsCutBySafeguards) {
  Json limited = with("steps", 100.0);
  limited["stress_limited_steps"] = 11.0;
  EXPECT_TRUE(says(warnings_for(limited), "safeguard: 11 of 100 steps"));
  limited["stress_limited_steps"] = 10.0;
  EXPECT_TRUE(warnings_for(limited).empty());

  // ispfem: nominal increment end_time / load_steps = 1 s / 100; max_step_cuts 8 fail the run
  // at 0.01 / 256; within two halvings (below 0.01 / 64 = 1.5625e-4 s) it warns.
  Json newton = Json::object();
  newton["newton"] = with("increment_min", 1.5e-4);
  newton["newton"]["cuts"] = 43.0;
  EXPECT_TRUE(says(warnings_for(newton), "safeguard: Newton needed increments down to 0.00015 s"));
  newton["newton"]["increment_min"] = 1.6e-4;
  EXPECT_TRUE(warnings_for(newton).empty());
}

// A footing pushed down onto a block, its reaction the run's measure.
const char* kFooting = R"(
spacing = 0.25
[time]
end_time = 1.0
[material.clay]
model = "tresca"
density = 1800.0
E = 1.0e6
nu = 0.3
cu = 1.0e4
[body.soil]
material = "clay"
min = [0.0, 0.0]
max = [2.0, 1.0]
[rigid_body.footing]
vertices = [[0.0, 1.0], [0.5, 1.0], [0.5, 1.2], [0.0, 1.2]]
velocity = [[0.0, 0.0, -0.05]]
)";

TEST(RunWarnings, AMovingBodyThatNeverCarriedAForceIsNamed) {
  const Scene scene = load_scene_checked_from_string(kFooting, "footing.toml", {});
  KineticEnergyRecord energy;
  const EnergyBudget budget(scene, Particles{}, 0.0);
  const auto warnings = [&](const Scene& s, double largest) {
    return run_warnings(s, /*inertial=*/false, energy, budget, 1.0, Json::object(), 100,
                        {{"footing", largest}});
  };
  EXPECT_TRUE(says(warnings(scene, 0.0), "rigid_body.footing moved but carried no force"));
  EXPECT_TRUE(warnings(scene, 1e-3).empty());
  // A body that stays where it is may well touch nothing.
  const Scene still = load_scene_checked_from_string(
      kFooting, "footing.toml", {"rigid_body.footing.velocity=[[0.0, 0.0, 0.0]]"});
  EXPECT_TRUE(warnings(still, 0.0).empty());
}

TEST(RunWarnings, SoilMovingFasterThanWhatDrivesItIsNotAtRest) {
  // Soil of 2 m x 1 m at 1800 kg/m^3 (3,600 kg/m) under a footing driven at 0.05 m/s: all of it
  // at that speed has 1/2 M v^2 = 4.5 J/m.
  const Scene scene = load_scene_checked_from_string(kFooting, "footing.toml", {});
  const EnergyBudget budget(scene, Particles{}, 0.0);
  const auto warnings = [&](double end_energy, bool inertial) {
    KineticEnergyRecord energy;
    energy.record(0.5, 100.0);
    energy.record(1.0, end_energy);
    energy.end_carriers.mass = 3600.0;
    return run_warnings(scene, inertial, energy, budget, 1.0, Json::object(), 100,
                        {{"footing", 1e3}});
  };
  EXPECT_TRUE(warnings(1.0, true).empty());  // a mechanism moving part of it at about 0.05 m/s
  const auto fast = warnings(9.0, true);
  ASSERT_EQ(fast.size(), 1u);
  EXPECT_TRUE(says(fast, "not at rest while driven")) << fast.front();
  EXPECT_NE(fast.front().find("9 J/m, is 2 times what all of it would have at the fastest driven "
                              "speed, 0.05 m/s"),
            std::string::npos)
      << fast.front();
  EXPECT_TRUE(warnings(9.0, false).empty());  // a quasi-static run's kinetic energy is not its own
}

TEST(LoadDrop, IsTheLargestFallBelowTheRunningMaximum) {
  // issue 44's ispfem footing: the load climbs to 110 kPa and falls to 57 kPa
  const LoadDrop d = largest_load_drop({0, 1, 2, 3, 4}, {0, 100, 110, 57, 60});
  EXPECT_NEAR(d.fraction, 53.0 / 110.0, 1e-12);
  EXPECT_EQ(d.peak, 110.0);
  EXPECT_EQ(d.peak_time, 2.0);
  EXPECT_EQ(d.low, 57.0);
  EXPECT_EQ(d.low_time, 3.0);
  EXPECT_EQ(largest_load_drop({0, 1, 2}, {0, 50, 100}).fraction, 0.0);  // rising: none
}

TEST(LoadDrop, FirstContactsSmallLoadsAreNotCounted) {
  // 5 -> 1 is a fall of 80 %, below a tenth of the largest load (100): contact noise
  EXPECT_EQ(largest_load_drop({0, 1, 2, 3, 4}, {0, 5, 1, 50, 100}).fraction, 0.0);
  EXPECT_NEAR(largest_load_drop({0, 1, 2, 3}, {0, 20, 10, 100}).fraction, 0.5, 1e-12);
}

TEST(LoadDrop, RecordedAlongTheMotionWhileTheBodyIsDriven) {
  // The footing pushed down at 0.05 m/s until t = 1 s, then held: the soil's upward force is its
  // load while it moves; once held, nothing is recorded.
  const Scene scene = load_scene_checked_from_string(
      kFooting, "footing.toml",
      {"rigid_body.footing.velocity=[[0.0, 0.0, -0.05], [1.0, 0.0, -0.05], [1.0, 0.0, 0.0]]"});
  std::vector<BoundaryLoad> loads = driven_boundaries(scene);
  ASSERT_EQ(loads.size(), 1u);
  EXPECT_EQ(loads[0].name, "footing");
  record_boundary_loads(scene, 0.5, {{"footing", Vec2(3.0, 200.0)}}, loads);
  record_boundary_loads(scene, 1.5, {{"footing", Vec2(0.0, 100.0)}}, loads);
  EXPECT_EQ(loads[0].time, std::vector<double>{0.5});
  EXPECT_EQ(loads[0].load, std::vector<double>{200.0});
}

TEST(RunWarnings, ALoadDropWhereNothingCanSoftenIsWarned) {
  const Scene scene = load_scene_checked_from_string(kFooting, "footing.toml", {});
  KineticEnergyRecord energy;
  const EnergyBudget budget(scene, Particles{}, 0.0);
  const auto warnings = [&](const Scene& s, std::vector<double> load) {
    const std::vector<BoundaryLoad> loads = {{"footing", {0.0, 0.25, 0.5, 0.75, 1.0}, load}};
    return run_warnings(s, /*inertial=*/false, energy, budget, 1.0, Json::object(), 100,
                        {{"footing", 110.0}}, loads);
  };
  const std::vector<std::string> w = warnings(scene, {0, 100, 110, 57, 60});
  ASSERT_TRUE(says(w,
                   "load-drop: the load on footing fell 48 % below its maximum, from 110 N/m "
                   "at t = 0.5 s to 57 N/m at t = 0.75 s"))
      << (w.empty() ? "" : w[0]);
  EXPECT_TRUE(warnings(scene, {0, 100, 110, 105, 106}).empty());  // 4.5 %: within the noise
  // An explicit run's reactions ring about their trend: its falls say nothing
  const std::vector<BoundaryLoad> loads = {{"footing", {0.0, 0.25, 0.5}, {0, 110, 57}}};
  EXPECT_TRUE(run_warnings(scene, /*inertial=*/true, energy, budget, 1.0, Json::object(), 100,
                           {{"footing", 110.0}}, loads)
                  .empty());
}

TEST(RunWarnings, NoLoadDropWhereAMaterialCanSoftenOrTheStrengthIsReduced) {
  Scene scene;
  scene.materials.resize(2);
  scene.materials[0].model = "tresca";
  scene.materials[1].model = "drucker-prager";
  EXPECT_TRUE(cannot_soften(scene));
  scene.strength_reduction.factor = 1.2;  // c and phi fall during an srf trial
  EXPECT_FALSE(cannot_soften(scene));
  scene.strength_reduction.factor = 1.0;
  scene.materials[1].model = "hypoplastic";  // dense sand softens past its peak
  EXPECT_FALSE(cannot_soften(scene));
  scene.materials[1].model = "simhypo-sand";
  EXPECT_FALSE(cannot_soften(scene));
  scene.materials[1].model = "mohr-coulomb";
  EXPECT_TRUE(cannot_soften(scene));
  scene.materials[1].model = "linear-elastic";
  EXPECT_TRUE(cannot_soften(scene));
}

TEST(RunWarnings, AFootingStartingAboveTheSoilIsWarnedOfByTheRun) {
  // footing.toml's footing lifted 0.3 m off the soil and pushed 0.1 m: ispfem completes with a
  // bearing of 0 and says why; lifted less, it says when it first touched.
  const std::string out = (std::filesystem::temp_directory_path() /
                           ("duet-warn-untouched-" + std::to_string(::getpid())))
                              .string();
  const auto run_footing = [&](const std::string& sets, const std::string& method = "ispfem") {
    return test::run_duet("run '" + std::string(DUET_SOURCE_DIR) +
                          "/benchmarks/scenes/footing.toml' --method " + method +
                          " --spacing 0.25 " + sets + " --quiet --no-plots --out '" + out + "'");
  };
  const test::DuetResult r = run_footing(
      "--set time.end_time=2 --set 'rigid_body.footing.vertices=[[0.0, 5.3], [1.0, 5.3], [1.0, "
      "5.6], [0.0, 5.6]]'");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("duet: warning: rigid_body.footing moved but carried no force"),
            std::string::npos)
      << r.output;
  EXPECT_NE(test::read_text(out + "/metrics.json").find("rigid_body.footing moved but carried"),
            std::string::npos);
  // Lifted 0.1 m and pushed 0.2 m it touches halfway (espfem: at the nodes' contact distance,
  // dp / 2): the measures read 0 until then.
  const test::DuetResult late = run_footing(
      "--set time.end_time=4 --set 'rigid_body.footing.vertices=[[0.0, 5.1], [1.0, 5.1], [1.0, "
      "5.4], [0.0, 5.4]]'",
      "espfem");
  EXPECT_EQ(late.status, 0) << late.output;
  EXPECT_NE(late.output.find("duet: warning: rigid_body.footing carried no force until t ="),
            std::string::npos)
      << late.output;
  // The same footing on the soil carries its load and is not named.
  const test::DuetResult on = run_footing("--set time.end_time=0.2");
  EXPECT_EQ(on.status, 0) << on.output;
  EXPECT_EQ(on.output.find("carried no force"), std::string::npos) << on.output;
  std::filesystem::remove_all(out);
}

TEST(RunWarnings, SaidOnTheTerminalAndInMetrics) {
  // The sand column through SPH stopped at t = 0.1 s, mid-collapse: its kinetic energy is at its
  // peak when the run ends, so the deposit's measures are not final; the run completes and says
  // so. (This test once used the rough footing at dp 0.25, whose soil ended inside it while its
  // dummies lay outside its outline: benchmarks/RESULTS.md, "SPH's rigid bodies".)
  const std::string out = (std::filesystem::temp_directory_path() / "duet-warn-collapse").string();
  const test::DuetResult r =
      test::run_duet("run '" + std::string(DUET_SOURCE_DIR) +
                     "/benchmarks/scenes/collapse.toml' --method sph --spacing 0.01 --set "
                     "time.end_time=0.1 --quiet --no-plots --out '" +
                     out + "'");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("duet: warning: not at rest: the kinetic energy at t = 0.1"),
            std::string::npos)
      << r.output;
  EXPECT_NE(test::read_text(out + "/metrics.json").find("\"not at rest: the kinetic energy"),
            std::string::npos);
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace duet
