// `duet check`: validates and estimates without running. The SPH step count is a closed form:
// footing at dp 0.1, dt = cfl h / c = 0.05 x 0.1 sqrt(2) / 100 m/s = 7.07e-5 s, 4 s / dt = 56,569
// steps, the count the run itself takes when nothing else limits its step.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/benchmarks/child_run.hpp"

namespace duet {
namespace {

using Result = test::DuetResult;

Result duet(const std::string& arguments) {
  return test::run_duet(arguments);
}

const std::string kScenes = std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/";
const std::string kFooting = kScenes + "footing.toml";

TEST(CheckCommand, PrintsParticlesAndEachMethodsStepsWithoutRunning) {
  const Result r = duet("check '" + kFooting + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("body soil (clay, tresca): 2,500 particles"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("sph: time step at most 7.07e-05 s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("at least 56,569 steps"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ispfem: increments of 0.04 s, 100 of them"), std::string::npos)
      << r.output;
}

TEST(CheckCommand, EspfemsStepCountsTheBulkViscosityAndSaysWhenOnlyTheRunCanKnow) {
  // cavity.toml: b1 = 1 scales the step by sqrt(1 + b1^2) - b1 = 0.414 (Abaqus' stability limit
  // with bulk viscosity, as ExplicitSolver::time_step), the Gershgorin step on a lattice is 0.7
  // dp / c: 10 s / (0.414 x 0.5 x 0.7 x 0.35 m / 176 m/s); the run takes 33,772 steps
  const std::string cavity = kScenes + "cavity.toml";
  const Result viscous = duet("check '" + cavity + "' --method espfem");
  ASSERT_EQ(viscous.status, 0) << viscous.output;
  EXPECT_NE(viscous.output.find("x 0.414 for bulk_viscosity 1), about 34,762 steps"),
            std::string::npos)
      << viscous.output;
  // The hypoplastic collapse: the stress-increment limit makes the count a lower bound
  const std::string collapse = kScenes + "collapse.toml";
  const Result stiffening = duet("check '" + collapse + "' --method espfem");
  ASSERT_EQ(stiffening.status, 0) << stiffening.output;
  EXPECT_NE(stiffening.output.find("steps at least: spfem.stress_increment_limit"),
            std::string::npos)
      << stiffening.output;
}

TEST(CheckCommand, RefusesWhatWouldNotFitUnlessForced) {
  const Result r = duet("check '" + kFooting + "' --method sph --spacing 0.0005");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("about 1e+08 particles"), std::string::npos) << r.output;
  const Result forced = duet("check '" + kFooting + "' --method sph --spacing 0.0005 --force");
  EXPECT_EQ(forced.status, 0) << forced.output;
  EXPECT_NE(forced.output.find("about 1e+08 particles"), std::string::npos) << forced.output;
}

TEST(CheckCommand, BadInputIsExit2) {
  EXPECT_EQ(duet("check '" + kFooting + "' --spacing 0").status, 2);
  EXPECT_EQ(duet("check '" + kFooting + "' --method fem").status, 2);
}

TEST(CheckCommand, SaysSphsSoundSpeedIsTheScenesAsTheSolverUsesIt) {
  // footing.toml's clay: P-wave speed sqrt((K + 4G/3) / rho) = 176 m/s (E 1 MPa, nu 0.497), above
  // the scene's 100 m/s, which the solver keeps: its step is cfl 0.05 x 176 / 100 = 0.088
  // Courant numbers against the P-wave
  const Result r = duet("check '" + kFooting + "' --method sph");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("sound speed 100 m/s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the sound speed is sph.sound_speed as given (the solver does not raise "
                          "it to the soil's P-wave speed, here 176 m/s: the step is then 0.0882 "
                          "Courant numbers against it, not cfl 0.05)"),
            std::string::npos)
      << r.output;
  const Result fast = duet("check '" + kFooting + "' --method sph --set sph.sound_speed=200");
  ASSERT_EQ(fast.status, 0) << fast.output;
  EXPECT_NE(fast.output.find("sound speed 200 m/s"), std::string::npos) << fast.output;
  EXPECT_NE(fast.output.find("P-wave speed, here 176 m/s)"), std::string::npos) << fast.output;
}

const std::string kBadScenes = std::string(DUET_SOURCE_DIR) + "/tests/data/bad-scenes/";

TEST(CheckCommand, RefusesWhatRunRefusesWithTheSameMessage) {
  // issue 44: a body running 0.5 m past a wall, E = 20 meant in MPa; `duet run` refuses them
  // with exit 2 (BadScene in scenes_test.cpp), before any work, and so does `duet check`.
  for (const char* name : {"body-crossing-wall", "body-beyond-wall", "modulus-in-megapascals",
                           "strength-in-kilopascals"}) {
    const std::string path = kBadScenes + name + ".toml";
    const Result check = duet("check '" + path + "'");
    const Result run = duet("run '" + path + "' --method ispfem --out /nonexistent/never-written");
    EXPECT_EQ(check.status, 2) << check.output;
    EXPECT_EQ(run.status, 2) << run.output;
    const std::string message = check.output.substr(0, check.output.find('\n'));
    EXPECT_NE(message.find(path + ":"), std::string::npos) << message;
    EXPECT_NE(run.output.find(message), std::string::npos) << run.output;
  }
}

TEST(CheckCommand, AQuasiStaticMethodRefusesACollapseAsRunDoes) {
  // The column's free vertical face in cohesionless sand has no static equilibrium (issue 44)
  const std::string collapse = kScenes + "collapse.toml";
  const Result check = duet("check '" + collapse + "' --method ispfem");
  const Result run =
      duet("run '" + collapse + "' --method ispfem --out /nonexistent/never-written");
  EXPECT_EQ(check.status, 2) << check.output;
  EXPECT_EQ(run.status, 2) << run.output;
  const std::string message = check.output.substr(0, check.output.find('\n'));
  EXPECT_NE(message.find("no static equilibrium"), std::string::npos) << message;
  EXPECT_NE(run.output.find(message), std::string::npos) << run.output;
  // Asked of every method, the scene is valid: the others' estimates, ispfem's refusal
  const Result all = duet("check '" + collapse + "'");
  EXPECT_EQ(all.status, 0) << all.output;
  EXPECT_NE(all.output.find("ispfem: refused (duet run exits 2): body.column"), std::string::npos)
      << all.output;
  EXPECT_NE(all.output.find("espfem: time step"), std::string::npos) << all.output;
}

TEST(CheckCommand, AModulusInMegapascalsIsTakenWithForceAndSaidAsAWarning) {
  const std::string path = kBadScenes + "modulus-in-megapascals.toml";
  const Result refused = duet("check '" + path + "'");
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find("material.sand.E = 20: a modulus below 10 kPa"), std::string::npos)
      << refused.output;
  EXPECT_NE(refused.output.find("or --force if it is meant"), std::string::npos) << refused.output;
  const Result forced = duet("check '" + path + "' --force");
  EXPECT_EQ(forced.status, 0) << forced.output;
  EXPECT_NE(forced.output.find("duet: warning: " + path +
                               ": material.sand.E = 20: a modulus below 10 kPa"),
            std::string::npos)
      << forced.output;
  // compare takes --force too, and hands it to every run it starts
  const std::string jobs = ::testing::TempDir() + "duet-force-jobs.txt";
  const std::string out = ::testing::TempDir() + "duet-force-compare";
  EXPECT_EQ(
      duet("compare '" + path + "' --methods sph --out '" + out + "' --emit-jobs '" + jobs + "'")
          .status,
      2);
  const Result compare = duet("compare '" + path + "' --methods sph --out '" + out +
                              "' --emit-jobs '" + jobs + "' --force");
  EXPECT_EQ(compare.status, 0) << compare.output;
  EXPECT_NE(test::read_text(jobs).find(" '--force'"), std::string::npos) << test::read_text(jobs);
  std::filesystem::remove(jobs);
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace duet
