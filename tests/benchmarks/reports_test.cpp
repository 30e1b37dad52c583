// compare.csv / compare.md, the --target choice and the summary over benchmarks
// (benchmarks/reports.cpp, run_summary.cpp, accuracy_summary.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "benchmarks/accuracy_summary.hpp"
#include "benchmarks/reports.hpp"
#include "benchmarks/run_summary.hpp"

namespace duet {
namespace {

RunSummary make_run(const std::string& method, double spacing, double error, double seconds,
                    const std::string& status = "completed") {
  RunSummary r;
  r.scene = "collapse";
  r.method = method;
  r.spacing = spacing;
  r.particles = static_cast<long>(0.02 / (spacing * spacing));
  r.steps = 1000;
  r.wall_seconds = seconds;
  r.status = status;
  if (status == "completed") {
    r.accuracy["runout"] = {0.36 * (1 + error), 0.36, error, "Lube et al. as quoted by Peng 2015"};
    r.measures["runout"] = 0.36 * (1 + error);
  } else {
    r.failure_reason = "non-finite stress";
    r.failure_time = 0.1;
  }
  return r;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

TEST(TargetChoice, PicksCoarsestSpacingWhoseErrorsAreAllBelowTarget) {
  const std::vector<RunSummary> runs = {make_run("sph", 0.005, 0.20, 1.0),
                                        make_run("sph", 0.0035, 0.04, 3.0),
                                        make_run("sph", 0.0025, 0.02, 9.0)};
  const auto choices = choose_for_target(runs, 0.05);
  ASSERT_EQ(choices.size(), 1u);
  ASSERT_TRUE(choices[0].run.has_value());
  EXPECT_DOUBLE_EQ(choices[0].run->spacing, 0.0035);
}

TEST(TargetChoice, FailedRunNeverMeetsTarget) {
  const std::vector<RunSummary> runs = {make_run("espfem", 0.005, 0.0, 1.0, "failed"),
                                        make_run("espfem", 0.0025, 0.10, 4.0)};
  const auto choices = choose_for_target(runs, 0.05);
  ASSERT_EQ(choices.size(), 1u);
  EXPECT_FALSE(choices[0].run.has_value());
}

TEST(CompareMarkdown, ListsEveryMeasureScoredOrNot) {
  RunSummary r = make_run("sph", 0.005, 0.1, 2.0);
  r.measures["height"] = 0.0973;
  const std::string md = compare_markdown({r}, 0.0);
  EXPECT_NE(md.find("| runout | runout error | height |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.0973 |"), std::string::npos) << md;
}

TEST(CompareMarkdown, AnErrorIsSignedAndACurveSaysWhereItsLargestIs) {
  RunSummary under = make_run("ispfem", 0.1, 0.149, 2.0);
  under.accuracy["runout"].signed_error = -0.149;
  RunSummary curve = make_run("sph", 0.1, 0.056, 2.0);
  curve.accuracy["runout"].signed_error = 0.056;
  curve.accuracy["runout"].worst_at = 0.0496;
  const std::string md = compare_markdown({under, curve, make_run("espfem", 0.1, 0.02, 1.0)}, 0.0);
  EXPECT_NE(md.find("| -14.9 % |"), std::string::npos) << md;
  EXPECT_NE(md.find("| +5.6 % at 0.0496 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 2.0 % |"), std::string::npos) << md;  // no sign recorded
}

TEST(CompareMarkdown, AWarnedRunSaysSoAndItsWarningsFollowTheTable) {
  RunSummary warned = make_run("ispfem", 0.1, 0.05, 2.0);
  warned.warnings = {"load-drop: the load fell by 12 %"};
  const std::vector<RunSummary> runs = {warned, make_run("sph", 0.1, 0.02, 1.0)};
  const std::string md = compare_markdown(runs, 0.0);
  EXPECT_NE(md.find("| completed (warned: 1) |"), std::string::npos) << md;
  EXPECT_NE(md.find("- ispfem at spacing 0.1 m: load-drop: the load fell by 12 %"),
            std::string::npos)
      << md;
  EXPECT_EQ(compare_markdown(runs, 0.0, false).find("load-drop"), std::string::npos);
}

TEST(CompareCsv, EachRunHasItsWorstSignedErrorAndItsWarnings) {
  const auto dir = std::filesystem::temp_directory_path() / "duet_reports_test_warnings";
  std::filesystem::create_directories(dir);
  RunSummary under = make_run("ispfem", 0.1, 0.149, 2.0);
  under.accuracy["runout"].signed_error = -0.149;
  under.warnings = {"not at rest", "load-drop, 12 %"};
  write_compare_csv((dir / "compare.csv").string(), {under});
  const std::string csv = read_file(dir / "compare.csv");
  EXPECT_NE(csv.find(",max_signed_error,warnings,warning_messages\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",-0.149,2,\"not at rest | load-drop, 12 %\"\n"), std::string::npos) << csv;
}

TEST(CompareCsv, FailedRunsAppearWithTheirReason) {
  const auto dir = std::filesystem::temp_directory_path() / "duet_reports_test";
  std::filesystem::create_directories(dir);
  const std::vector<RunSummary> runs = {make_run("sph", 0.005, 0.1, 1.0),
                                        make_run("espfem", 0.005, 0.0, 0.5, "failed")};
  write_compare_csv((dir / "compare.csv").string(), runs);
  const std::string csv = read_file(dir / "compare.csv");
  std::istringstream lines(csv);
  std::string header, first, second;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_NE(header.find("accuracy.runout.rel_error"), std::string::npos);
  EXPECT_NE(first.find("sph,0.005"), std::string::npos);
  EXPECT_NE(second.find("failed,non-finite stress,0.1"), std::string::npos);
}

TEST(CompareMarkdown, ReportsTargetChoicePerMethod) {
  const std::vector<RunSummary> runs = {make_run("sph", 0.005, 0.2, 1.0),
                                        make_run("sph", 0.0025, 0.01, 5.0)};
  const std::string md = compare_markdown(runs, 0.05);
  EXPECT_NE(md.find("- sph: spacing 0.0025 m"), std::string::npos);
}

TEST(AccuracySummary, MarksARunThatWarnedOfItsOwnResult) {
  RunSummary doubted = make_run("ispfem", 0.25, 0.03, 3.0);
  doubted.warnings = {"load-drop: the load fell 23 % in a model that cannot soften"};
  BenchmarkRuns footing{"footing", "", {doubted, make_run("sph", 0.25, 0.04, 5.0)}};
  const std::string md = summary_markdown({footing}, 0.05);
  EXPECT_NE(
      md.find("| footing | ispfem | 1 of 1 | 0.25 m | 3 | 3 % (warned: 1) | 3 % (dp 0.25 m, 3 "
              "s (warned: 1)) |"),
      std::string::npos)
      << md;
  EXPECT_NE(md.find("| footing | sph | 1 of 1 | 0.25 m | 5 | 4 % | 4 % (dp 0.25 m, 5 s) |"),
            std::string::npos)
      << md;
}

TEST(AccuracySummary, NamesPerBenchmarkTheCoarsestSpacingAndTheCheapestMethod) {
  // footing: espfem meets 5 % only at 0.1 m (20 s), ispfem already at 0.25 m (3 s); sph fails
  // everywhere. collapse: nobody meets 5 %.
  BenchmarkRuns footing{"footing", "", {}};
  footing.runs = {make_run("sph", 0.25, 0.0, 1.5, "failed"), make_run("espfem", 0.25, 0.10, 2.8),
                  make_run("espfem", 0.1, 0.04, 20.0), make_run("ispfem", 0.25, 0.03, 3.0),
                  make_run("ispfem", 0.1, 0.02, 70.0)};
  BenchmarkRuns collapse{"collapse", "", {make_run("sph", 0.01, 0.2, 5.0)}};
  const std::string md = summary_markdown({footing, collapse}, 0.05);
  EXPECT_NE(md.find("| footing | sph | 0 of 1 | none | | | none completed: non-finite stress |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| footing | espfem | 2 of 2 | 0.1 m | 20 | 4 % | 4 % (dp 0.1 m, 20 s) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| footing | ispfem | 2 of 2 | 0.25 m | 3 | 3 % | 2 % (dp 0.1 m, 70 s) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| footing | ispfem (dp 0.25 m) | 3 | espfem, 20 s | 6.67 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| collapse | no method meets the target |"), std::string::npos) << md;
}

// README's demo block is the demo's own compare.md (benchmarks/results/demo/regenerate.sh copies
// it), not numbers typed by hand: the two agree line for line.
TEST(ReadmeDemo, TheBlockIsTheDemosCompareMdLessItsTitle) {
  const std::filesystem::path root = DUET_SOURCE_DIR;
  const std::string readme = read_file(root / "README.md");
  const std::string begin = "<!-- demo:begin -->\n", end = "<!-- demo:end -->";
  const auto from = readme.find(begin), to = readme.find(end);
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  const std::string block = readme.substr(from + begin.size(), to - from - begin.size());
  std::string table = read_file(root / "benchmarks/results/demo/compare.md");
  table = table.substr(table.find('\n') + 1);           // its title line
  table = table.substr(table.find_first_not_of('\n'));  // and the blank line after it
  while (!table.empty() && table.back() == '\n') table.pop_back();
  EXPECT_EQ(block, table + "\n");
  EXPECT_NE(block.find("| sph | 0.01 |"), std::string::npos) << block;
}

}  // namespace
}  // namespace duet
