// `duet run` draws a run's charts at the end and `duet plot` draws them again: for a footing, a
// cavity and a collapse the named PNGs exist, are PNG files and have the size matplotlib gives
// them (read from the PNG header); an unknown field is refused naming the fields there are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/benchmarks/child_run.hpp"

namespace duet {
namespace {

namespace fs = std::filesystem;

using test::png_size;
using test::PngSize;

void expect_chart(const fs::path& path, std::uint32_t min_width, std::uint32_t min_height) {
  ASSERT_TRUE(fs::exists(path)) << path;
  const PngSize size = png_size(path);
  EXPECT_GE(size.width, min_width) << path;
  EXPECT_GE(size.height, min_height) << path;
  EXPECT_LE(size.width, 3000u) << path;
  EXPECT_LE(size.height, 3000u) << path;
}

fs::path run(const std::string& scene, const std::string& method, const std::string& arguments) {
  const fs::path out = fs::temp_directory_path() / ("duet-plot-" + scene + "-" + method);
  fs::remove_all(out);
  const test::DuetResult r = test::run_duet(
      "run '" + std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/" + scene + ".toml' --method " +
      method + " " + arguments + " --quiet --out '" + out.string() + "'");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("chart: " + (out / "series.png").string()), std::string::npos)
      << r.output;
  return out;
}

TEST(PlotCommand, FootingLoadAgainstSettlement) {
  const fs::path out = run("footing", "espfem", "--spacing 0.25 --set time.end_time=0.2");
  expect_chart(out / "series.png", 600, 300);
  expect_chart(out / "load_footing.png", 400, 300);
  expect_chart(out / "snapshots_von_mises.png", 900, 300);
  fs::remove_all(out);
}

TEST(PlotCommand, CavityPressureAgainstExpansion) {
  const fs::path out =
      run("cavity", "ispfem",
          "--spacing 0.5 --set time.end_time=0.5 --set spfem.implicit.load_steps=5");
  expect_chart(out / "expansion_cavity.png", 400, 300);
  expect_chart(out / "snapshots_von_mises.png", 900, 300);
  fs::remove_all(out);
}

TEST(PlotCommand, CollapseRunOutAndHeightAndAChosenField) {
  const fs::path out = run("collapse", "sph", "--spacing 0.01 --set time.end_time=0.1");
  expect_chart(out / "collapse_column.png", 600, 300);
  expect_chart(out / "snapshots_von_mises.png", 900, 150);
  // Drawn again with another field.
  const test::DuetResult again = test::run_duet("plot '" + out.string() + "' --field pressure");
  EXPECT_EQ(again.status, 0) << again.output;
  expect_chart(out / "snapshots_pressure.png", 900, 150);
  const test::DuetResult wrong = test::run_duet("plot '" + out.string() + "' --field presure");
  EXPECT_EQ(wrong.status, 2) << wrong.output;
  EXPECT_NE(wrong.output.find("no field 'presure'"), std::string::npos) << wrong.output;
  EXPECT_NE(wrong.output.find("pressure"), std::string::npos) << wrong.output;
  fs::remove_all(out);
}

TEST(PlotCommand, NoPlotsDrawsNothingAndAFolderWithoutARunIsRefused) {
  const fs::path out = fs::temp_directory_path() / "duet-plot-none";
  fs::remove_all(out);
  const test::DuetResult r = test::run_duet(
      "run '" + std::string(DUET_SOURCE_DIR) +
      "/benchmarks/scenes/collapse.toml' --method sph --spacing 0.02 --set time.end_time=0.01 "
      "--quiet --no-plots --out '" +
      out.string() + "'");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(fs::exists(out / "series.png"));
  const test::DuetResult empty =
      test::run_duet("plot '" + fs::temp_directory_path().string() + "/duet-plot-no-such-run'");
  EXPECT_EQ(empty.status, 2) << empty.output;
  EXPECT_NE(empty.output.find("no metrics.json"), std::string::npos) << empty.output;
  fs::remove_all(out);
}

}  // namespace
}  // namespace duet
