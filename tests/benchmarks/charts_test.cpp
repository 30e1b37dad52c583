// Every chart script drawn from a small fixture (tests/data/charts/): the PNG exists and has the
// size its layout gives, failed runs' reasons listed under the chart make it taller, and nothing
// is printed (no library warning reaches the terminal). Looked at by eye when they change:
// benchmarks/RESULTS.md "Charts".
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "benchmarks/plotting.hpp"
#include "tests/benchmarks/child_run.hpp"

namespace duet {
namespace {

namespace fs = std::filesystem;

using test::png_size;
using test::PngSize;

/// Runs a chart script with Debian's python, returning what it printed.
std::string draw(const std::string& script, const std::vector<std::string>& arguments) {
  std::string command =
      plotting_python() + " '" + DUET_SOURCE_DIR + "/benchmarks/plot/" + script + "'";
  for (const std::string& a : arguments) command += " '" + a + "'";
  const test::DuetResult r = test::run_command(command);
  EXPECT_EQ(r.status, 0) << command << "\n" << r.output;
  const std::string output = r.output;
  return output;
}

const std::string kFixtures = std::string(DUET_SOURCE_DIR) + "/tests/data/charts/";

class Charts : public testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(plotting_python().empty()) << "no python3 with matplotlib";
    // One folder per test: ctest runs the tests of this file side by side.
    out_ =
        fs::temp_directory_path() / (std::string("duet-charts-") +
                                     testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(out_);
  }
  void TearDown() override { fs::remove_all(out_); }
  fs::path out_;
};

TEST_F(Charts, CompareWithScoredErrorAndFailedRuns) {
  const fs::path png = out_ / "compare.png";
  EXPECT_EQ(draw("compare.py", {kFixtures + "compare-scored.csv", png.string(), "collapse"}), "");
  const PngSize size = png_size(png);
  // 7 x 5.2 in at 120 dpi
  EXPECT_NEAR(size.width, 840, 1);   // matplotlib rounds down
  EXPECT_NEAR(size.height, 624, 1);  // matplotlib rounds down
}

TEST_F(Charts, CompareWithoutScoredMeasureDrawsEachMeasure) {
  const fs::path png = out_ / "compare.png";
  EXPECT_EQ(draw("compare.py", {kFixtures + "compare-unscored.csv", png.string(), "collapse"}), "");
  const PngSize size = png_size(png);
  // two measures: 9 x (2 x 2.8 + 0.8) in at 120 dpi
  EXPECT_NEAR(size.width, 1080, 1);  // matplotlib rounds down
  EXPECT_NEAR(size.height, 768, 1);  // matplotlib rounds down
}

TEST_F(Charts, StabilityGrowsToListLongReasons) {
  const fs::path png = out_ / "stability.png";
  EXPECT_EQ(draw("stability.py", {kFixtures + "stability.csv", png.string(), "collapse (sph)",
                                  "sph.cfl=-", "sph.alpha=-"}),
            "");
  const PngSize size = png_size(png);
  // 3 x 2 cells: (1.9 x 3 + 2.6) x (1.15 x 2 + 2.2) in, plus the two lines of the long reason
  EXPECT_NEAR(size.width, 996, 1);  // matplotlib rounds down
  EXPECT_GT(size.height, 540u);
  EXPECT_LT(size.height, 640u);
}

TEST_F(Charts, StabilitySplitsACellPerFurtherKey) {
  // Three varied keys: 2 x 1 cells, each split in two by the third (once they were drawn over each
  // other, their labels overprinted)
  const fs::path png = out_ / "stability-three.png";
  EXPECT_EQ(draw("stability.py",
                 {kFixtures + "stability-three-keys.csv", png.string(), "collapse (espfem)"}),
            "");
  const PngSize size = png_size(png);
  // (1.9 x 2 columns x 2 sub-cells + 2.6) x (1.15 + 2.2) in at 120 dpi
  EXPECT_NEAR(size.width, 1224, 1);
  EXPECT_NEAR(size.height, 402, 1);
}

TEST_F(Charts, SummaryGridOfBenchmarks) {
  const fs::path png = out_ / "summary.png";
  EXPECT_EQ(draw("summary.py", {kFixtures + "summary.csv", png.string(), "0.05"}), "");
  const PngSize size = png_size(png);
  // Four benchmarks: 3 columns x 2 lines of 3.6 x 3.0 in, 0.5 in for the legend, at 110 dpi.
  EXPECT_NEAR(size.width, 1188, 1);
  EXPECT_NEAR(size.height, 715, 1);
}

TEST_F(Charts, ElementChart) {
  const fs::path png = out_ / "element.png";
  EXPECT_EQ(draw("element.py", {kFixtures + "element.csv", png.string(), "drucker-prager"}), "");
  const PngSize size = png_size(png);
  EXPECT_GT(size.width, 600u);
  EXPECT_GT(size.height, 300u);
}

}  // namespace
}  // namespace duet
