// A grid run three ways gives the same tables: `duet stability` in one process, over child
// processes (--jobs 2), and from its --emit-jobs file run by a shell and then `duet collect`;
// the same for `duet compare`. Wall times and per-phase timings differ between runs and are
// left out of the comparison; every other column must match. A cell that never ran is listed
// as "not run".
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/benchmarks/child_run.hpp"

namespace duet {
namespace {

namespace fs = std::filesystem;

const std::string kScene = std::string(DUET_SOURCE_DIR) + "/benchmarks/scenes/collapse.toml";
const std::string kSmall = "--set spacing=0.02 --set time.end_time=0.02";

/// The CSV without the columns that measure time (wall_seconds, timing.*).
std::vector<std::string> timeless(const std::string& csv_text) {
  std::istringstream in(csv_text);
  std::string line;
  std::vector<std::string> rows;
  std::vector<bool> keep;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::string field;
    bool quoted = false;
    for (const char c : line) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted) {
        fields.push_back(field);
        field.clear();
      } else {
        field += c;
      }
    }
    fields.push_back(field);
    if (keep.empty()) {
      for (const std::string& name : fields)
        keep.push_back(name != "wall_seconds" && name.rfind("timing.", 0) != 0);
    }
    std::string row;
    for (std::size_t k = 0; k < fields.size() && k < keep.size(); ++k) {
      if (keep[k]) row += fields[k] + "|";
    }
    rows.push_back(row);
  }
  return rows;
}

class RunGrid : public testing::Test {
 protected:
  void SetUp() override {
    // One folder per test: ctest runs the tests of this file side by side.
    root_ =
        fs::temp_directory_path() /
        (std::string("duet-grid-") + testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  test::DuetResult duet(const std::string& arguments) {
    test::DuetResult r = test::run_duet(arguments);
    EXPECT_EQ(r.status, 0) << arguments << "\n" << r.output;
    return r;
  }
  fs::path root_;
};

TEST_F(RunGrid, StabilityThreeWaysGivesTheSameTable) {
  const std::string grid = "stability '" + kScene + "' --method sph " + kSmall +
                           " --vary sph.cfl=0.05,0.1 --vary sph.alpha=0.5,1 --out ";
  duet(grid + "'" + (root_ / "direct").string() + "' --jobs 1");
  duet(grid + "'" + (root_ / "children").string() + "' --jobs 2");
  const fs::path jobs = root_ / "jobs.txt";
  const test::DuetResult emitted =
      duet(grid + "'" + (root_ / "emitted").string() + "' --emit-jobs '" + jobs.string() + "'");
  EXPECT_NE(emitted.output.find("4 cells written"), std::string::npos) << emitted.output;
  EXPECT_FALSE(fs::exists(root_ / "emitted" / "stability.csv"));  // nothing ran
  ASSERT_EQ(std::system(("bash '" + jobs.string() + "' > /dev/null 2>&1").c_str()), 0);
  duet("collect '" + (root_ / "emitted").string() + "'");

  const auto direct = timeless(test::read_text(root_ / "direct" / "stability.csv"));
  ASSERT_EQ(direct.size(), 5u);  // header + 4 cells
  EXPECT_NE(direct[1].find("completed"), std::string::npos) << direct[1];
  EXPECT_EQ(timeless(test::read_text(root_ / "children" / "stability.csv")), direct);
  EXPECT_EQ(timeless(test::read_text(root_ / "emitted" / "stability.csv")), direct);
  EXPECT_TRUE(fs::exists(root_ / "emitted" / "stability.png"));
  EXPECT_TRUE(fs::exists(root_ / "children" / "sph.cfl=0.1_sph.alpha=1" / "run.log"));
}

TEST_F(RunGrid, CompareFromEmittedJobsAndACellNotRun) {
  const std::string grid = "compare '" + kScene +
                           "' --methods sph,espfem --spacings 0.02,0.025 --set time.end_time=0.02"
                           " --out ";
  duet(grid + "'" + (root_ / "direct").string() + "'");
  const fs::path jobs = root_ / "jobs.txt";
  duet(grid + "'" + (root_ / "emitted").string() + "' --emit-jobs '" + jobs.string() + "'");
  // Run all but the last line: that cell shows as not run.
  ASSERT_EQ(std::system(("head -n 3 '" + jobs.string() + "' | bash > /dev/null 2>&1").c_str()), 0);
  duet("collect '" + (root_ / "emitted").string() + "'");
  const auto direct = timeless(test::read_text(root_ / "direct" / "compare.csv"));
  const auto emitted = timeless(test::read_text(root_ / "emitted" / "compare.csv"));
  ASSERT_EQ(direct.size(), 5u);
  ASSERT_EQ(emitted.size(), 5u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(emitted[k], direct[k]) << k;
  EXPECT_NE(emitted[4].find("not run"), std::string::npos) << emitted[4];
  // Run the last one too: now the tables agree.
  ASSERT_EQ(std::system(("tail -n 1 '" + jobs.string() + "' | bash > /dev/null 2>&1").c_str()), 0);
  duet("collect '" + (root_ / "emitted").string() + "'");
  EXPECT_EQ(timeless(test::read_text(root_ / "emitted" / "compare.csv")), direct);
}

TEST_F(RunGrid, CollectRefusesAFolderWithoutAGrid) {
  const test::DuetResult r = test::run_duet("collect '" + root_.string() + "'");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("no grid.json"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace duet
