// `duet check`: validates and estimates without running. The SPH step count is a closed form:
// footing at dp 0.1, dt = cfl h / c = 0.05 x 0.1 sqrt(2) / 100 m/s = 7.07e-5 s, 4 s / dt = 56,569
// steps, the count the run itself takes when nothing else limits its step.
#include <gtest/gtest.h>

#include <string>

#include "tests/benchmarks/child_run.hpp"

namespace duet {
namespace {

using Result = test::DuetResult;

Result duet(const std::string& arguments) {
  return test::run_duet(arguments);
}

const std::string kFooting = std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/footing.toml";

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

}  // namespace
}  // namespace duet
